# SPDX-License-Identifier: GPL-3.0-or-later
"""Application handlers: the paper and the primitive objects follow the current frame; undo and
redo show the paper as it was at that step; saving packs the paper; loading a file clears the
runtime's caches (``blender.runtime``)."""

from __future__ import annotations

import time

import bpy
from bpy.app.handlers import persistent

from . import checks, frames, images, playback, runtime, surfaces

FRAME_BUDGET_S = 0.5  # simulation a frame change may take while the artist works
CATCH_UP_SLICE_S = 0.1  # then the rest is simulated in slices of this, between UI events


def exact_frames() -> bool:
    """Rendering (or a command-line render) needs every frame exact, however long it takes."""
    return bpy.app.background or bpy.app.is_job_running("RENDER")


def _report(scene, message: str):
    rt = runtime.get()
    if message != rt.last_error:
        print(f"Virtual Hairy Brush: frame {scene.frame_current}: {message}")
    rt.last_error = message


def follow_frame(scene) -> bool:
    """Show the artwork as it is at the scene's current frame. Returns whether it did. While
    the artist works, a frame change simulates for at most FRAME_BUDGET_S; a longer catch-up
    goes on in slices from a timer (another frame change, or turning Follow Frames off, stops
    it). No exception leaves this function: a handler must not break Blender's frame changes."""
    st = checks.settings(scene)
    if (
        runtime.get().suspended
        or not st.sync_frames
        or st.recording is None
        or st.paper_object is None
    ):
        return False
    frame = scene.frame_current + scene.frame_subframe
    try:
        with surfaces.trusting_digests():  # the mesh is read again only after it changed
            pb = playback.playback_for(scene)
            target = frames.samples_at_frame(pb.rec, scene, frame)
            sim = playback.show(scene, target, should_stop=_deadline(exact_frames()))
    except checks.USER_ERRORS as exc:
        _report(scene, str(exc))
        return False
    except MemoryError:
        _report(scene, "not enough memory for this paper: lower its resolution")
        return False
    except Exception as exc:  # a handler must not raise into Blender
        _report(scene, f"unexpected error ({type(exc).__name__}: {exc})")
        return False
    runtime.get().last_error = ""
    if sim.index < target:
        _catch_up_later(scene.name, frame, target)
    return True


def _deadline(exact: bool):
    if exact:
        return None
    end = time.perf_counter() + FRAME_BUDGET_S
    return lambda: time.perf_counter() > end


def _catch_up_later(scene_name: str, frame: float, target: int):
    """Go on simulating toward ``target`` in slices between UI events, with a progress bar."""
    wm = bpy.context.window_manager

    def slice_():
        scene = bpy.data.scenes.get(scene_name)
        if scene is None or scene.frame_current + scene.frame_subframe != frame:
            wm.progress_end()
            return None
        if not checks.settings(scene).sync_frames:
            wm.progress_end()
            return None
        try:
            end = time.perf_counter() + CATCH_UP_SLICE_S
            with surfaces.trusting_digests():
                sim = playback.show(scene, target, should_stop=lambda: time.perf_counter() > end)
        except Exception as exc:  # a timer must not raise into Blender
            _report(scene, f"catching up: {exc}")
            wm.progress_end()
            return None
        wm.progress_update(int(100 * sim.index / max(target, 1)))
        if sim.index >= target:
            wm.progress_end()
            return None
        return 0.01

    wm.progress_begin(0, 100)
    runtime.get().start_timer(slice_, first_interval=0.01)


@persistent
def on_frame_change(scene, _depsgraph=None):
    follow_frame(scene)


@persistent
def on_depsgraph_update(_scene, depsgraph=None):
    """A mesh's geometry changed (an edit, a script that told the depsgraph): the paper mesh's
    kept digest is computed again at the next frame change."""
    updates = depsgraph.updates if depsgraph is not None else ()
    if any(isinstance(u.id, bpy.types.Mesh) and u.is_updated_geometry for u in updates):
        runtime.get().digests.clear()


@persistent
def on_undo_redo(_scene, _data=None):
    # Undo brings back the recording and the image's record of how many samples it showed, but
    # not its pixels: show that many samples of the recording again (the playback is kept while
    # the recording and settings are unchanged, so this costs a seek).
    rt = runtime.get()
    rt.views.clear()  # image buffers may no longer hold what was shown
    rt.digests.clear()  # the meshes may be back as they were
    for scene in bpy.data.scenes:
        st = checks.settings(scene)
        img = st.paper_image
        if img is None or images.SHOWN_TAG not in img:
            continue
        try:
            if st.recording is None:
                images.show_blank(st, surfaces.paper_texture(st))
            else:
                target = int(img[images.SHOWN_TAG])
                sim = playback.show(scene, target, should_stop=_deadline(exact_frames()))
                if sim.index < target:  # a long way from a snapshot: the rest from a timer
                    frame = scene.frame_current + scene.frame_subframe
                    _catch_up_later(scene.name, frame, target)
        except Exception as exc:  # a handler must not raise into Blender
            print(f"Virtual Hairy Brush: undo: {exc}")


@persistent
def on_save_pre(_filepath="", _data=None):
    # changed pixels, or an image that Image > Save As unpacked: the .blend keeps what is shown
    for img in bpy.data.images:
        if images.PAPER_TAG in img and (img.is_dirty or img.packed_file is None):
            try:
                images.pack_image(img)
            except RuntimeError as exc:  # no pixels to pack (its file is gone): saved as it is
                print(f"Virtual Hairy Brush: cannot pack '{img.name}': {exc}")


@persistent
def on_load_post(_filepath="", _data=None):
    runtime.get().clear()  # playbacks, image views, meshes of another file


_HANDLERS = (
    ("frame_change_post", on_frame_change),
    ("depsgraph_update_post", on_depsgraph_update),
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
