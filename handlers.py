# SPDX-License-Identifier: GPL-3.0-or-later
"""Application handlers: the paper and the primitive objects follow the current frame; undo and
redo show the paper as it was at that step; saving packs the paper; loading a file drops the
playback caches."""

from __future__ import annotations

import contextlib

import bpy
from bpy.app.handlers import persistent

from . import bridge, playback
from .sim.recording import RecordingError

_suspend = 0
last_error = ""


@contextlib.contextmanager
def suspended():
    """Frame changes made by our own operators (baking samples) must not simulate."""
    global _suspend
    _suspend += 1
    try:
        yield
    finally:
        _suspend -= 1


def follow_frame(scene) -> bool:
    """Show the artwork as it is at the scene's current frame. Returns whether it did."""
    global last_error
    st = bridge.settings(scene)
    if _suspend or not st.sync_frames or st.recording is None or st.paper_object is None:
        return False
    try:
        playback.show_frame(scene, scene.frame_current + scene.frame_subframe)
    except (bridge.UserError, RecordingError) as exc:
        if str(exc) != last_error:
            print(f"Virtual Hairy Brush: frame {scene.frame_current}: {exc}")
        last_error = str(exc)
        return False
    last_error = ""
    return True


@persistent
def on_frame_change(scene, _depsgraph=None):
    follow_frame(scene)


@persistent
def on_undo_redo(_scene, _data=None):
    # Undo brings back the recording and the image's record of how many samples it showed, but
    # not its pixels: show that many samples of the recording again (the playback is kept while
    # the recording and settings are unchanged, so this costs a seek).
    bridge.forget_views()
    for scene in bpy.data.scenes:
        st = bridge.settings(scene)
        img = st.paper_image
        if img is None or bridge.SHOWN_TAG not in img:
            continue
        try:
            if st.recording is None:
                bridge.show_blank(st)
            else:
                playback.show(scene, int(img[bridge.SHOWN_TAG]))
        except (bridge.UserError, RecordingError) as exc:
            print(f"Virtual Hairy Brush: undo: {exc}")


@persistent
def on_save_pre(_filepath="", _data=None):
    for img in bpy.data.images:
        if bridge.PAPER_TAG in img and img.is_dirty:
            bridge.pack_image(img)


@persistent
def on_load_post(_filepath="", _data=None):
    playback.clear()
    bridge.forget_views()


_HANDLERS = (
    ("frame_change_post", on_frame_change),
    ("undo_post", on_undo_redo),
    ("redo_post", on_undo_redo),
    ("save_pre", on_save_pre),
    ("load_post", on_load_post),
)


def register():
    for name, fn in _HANDLERS:
        lst = getattr(bpy.app.handlers, name)
        if fn not in lst:
            lst.append(fn)


def unregister():
    for name, fn in reversed(_HANDLERS):
        lst = getattr(bpy.app.handlers, name)
        while fn in lst:
            lst.remove(fn)
    playback.clear()
