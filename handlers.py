# SPDX-License-Identifier: GPL-3.0-or-later
"""Application handlers: the paper and the primitive objects follow the current frame; undo and
redo bring back the paper image's packed pixels; saving packs the paper; loading a file drops
the playback caches."""

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
    # Undo restores the image datablock with its packed file but keeps the old pixel buffer;
    # reloading reads the packed pixels of the restored step.
    for img in bpy.data.images:
        if bridge.PAPER_TAG in img and img.packed_file is not None:
            img.reload()
    # the playback cache is keyed by the recording and settings: still valid if they are


@persistent
def on_save_pre(_filepath="", _data=None):
    for img in bpy.data.images:
        if bridge.PAPER_TAG in img and img.is_dirty:
            bridge.pack_image(img)


@persistent
def on_load_post(_filepath="", _data=None):
    playback.clear()


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
