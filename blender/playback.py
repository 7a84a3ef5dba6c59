# SPDX-License-Identifier: GPL-3.0-or-later
"""The artwork at any frame: one engine Simulation per scene, moved to the sample a frame asks
for. A move restores the nearest snapshot at or before the target (backwards or forwards) and
steps on from there, so frame N always gives exactly the image of simulating straight to N.
A work's grid and seal (sim.writing.work) are drawn on the paper image as ``sim render`` draws
them. Also the NURBS surface objects that show the writing primitives (Sec. 2, 6)."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import bpy

from ..sim.engine.checkpoints import CacheError, load_checkpoints
from ..sim.engine.simulation import Simulation
from ..sim.engine.timeline import Timeline
from ..sim.writing.work.compose import check_work, work_of
from ..sim.writing.work.overlay import Overlay, work_image8
from . import checks, frames, images, primitives, recordings, runtime, surfaces

MAX_SNAPSHOT_EVERY = 64  # samples


class Playback:
    """The scene's simulation on a Timeline (delta snapshots, see sim.timeline): a snapshot
    every frame's worth of samples, so a step of one frame back or forth re-simulates at most
    one frame."""

    cache_warning = ""  # why the farm cache next to the .blend was not used ("": it was, or none)

    def __init__(self, rec, key: str, samples_per_frame: float = 5.0, surface=None):
        self.key = key
        self.rec = rec
        every = int(min(max(round(samples_per_frame), 1), MAX_SNAPSHOT_EVERY))
        sim = Simulation(rec, surface=surface)  # surface: the mesh's SurfacePaper, or flat
        self.timeline = Timeline(sim, every, checks.SNAPSHOT_BUDGET_BYTES)
        self.overlay = work_overlay(rec, sim.paper)

    def image8(self, sim: Simulation):
        """The paper's image as ``sim render`` writes it (a work's grid and seal with the ink):
        RGB uint8, top row first."""
        work = work_of(self.rec) if self.overlay is not None else None
        return work_image8(sim.paper, work, self.rec.seed)

    @property
    def sim(self) -> Simulation:
        return self.timeline.sim

    def seek(self, index: int, progress=None, should_stop=None) -> Simulation:
        return self.timeline.seek(index, progress, should_stop)


def work_overlay(rec, paper):
    """The grid and seal of a recording's work (sim.writing.work) on its paper, as ``sim
    render`` draws them; None for a recording without a work or a work with neither."""
    work = work_of(rec)
    if work is None:
        return None
    over = Overlay(work, paper.W, paper.H, paper.ppm, rec.seed)
    return over if over.boxes or over.seal is not None else None


def cache_key(scene) -> str:
    """Identifies the stored recording text and every setting that renders it; cheap, so a
    frame change does not re-parse and re-validate an unchanged recording."""
    st = checks.settings(scene)
    text = st.recording.as_string() if st.recording is not None else ""
    h = hashlib.sha1(text.encode("utf-8"), usedforsecurity=False)
    h.update(json.dumps(recordings.scene_overrides(st), sort_keys=True).encode("utf-8"))
    h.update(repr((scene.frame_start, scene.render.fps, scene.render.fps_base)).encode())
    h.update(surfaces.surface_digest(st).encode())  # writing on a mesh: the mesh as it is
    return h.hexdigest()


CACHE_EVERY = 256  # samples between the farm cache's checkpoints (see operators/bake_cache)


def cache_folder(scene):
    """Where the farm cache of ``scene`` lives, next to the saved .blend (None: not saved)."""
    if not bpy.data.filepath:
        return None
    blend = Path(bpy.data.filepath)
    safe = "".join(c if c.isalnum() or c in "-_." else "_" for c in scene.name)
    return blend.parent / f"hairy_brush_cache_{blend.stem}" / safe


def _load_cache(pb: Playback, scene):
    """A fresh playback starts from the farm cache's checkpoints when they are provably this
    scene's (every file checked); any other cache is ignored with a warning, once a playback."""
    folder = cache_folder(scene)
    if folder is None or not folder.exists():
        return
    try:
        load_checkpoints(pb.timeline, folder, pb.key)
    except CacheError as exc:
        pb.cache_warning = f"farm cache {folder} not used: {exc}; simulating from the start"
        print(f"Virtual Hairy Brush: {pb.cache_warning}")


def playback_for(scene) -> Playback:
    """The scene's Playback, rebuilt only when the recording or a setting changed; a recording
    that failed to load fails again at once until it or a setting changes."""
    key = cache_key(scene)
    rt = runtime.get()
    pb = rt.playbacks.get(scene.name)
    failed = rt.failed.get(scene.name)
    if failed is not None and failed[0] == key:
        raise checks.UserError(failed[1])
    if pb is None or pb.key != key:
        try:
            rec = recordings.recording_from_scene(scene)
            check_work(rec)  # a work's layout and seal (drawn on the paper), as sim render does
            surface = surfaces.surface_paper(checks.settings(scene), rec)
            per = frames.timeline(rec, scene)[1]  # frames per sample
            pb = Playback(rec, key, samples_per_frame=1.0 / per, surface=surface)
        except checks.USER_ERRORS as exc:
            rt.failed[scene.name] = (key, str(exc))
            raise
        _load_cache(pb, scene)
        rt.playbacks[scene.name] = pb
    return pb


def adopt(scene, sim: Simulation):
    """After a live stroke was stored: the scene's Playback goes on from the live simulation
    (same samples, same state) instead of simulating the whole recording again."""
    pb = runtime.get().playbacks.get(scene.name)
    if pb is None or pb.sim is not sim:
        return
    pb.key, pb.rec = cache_key(scene), sim.rec


def show(scene, index: int, progress=None, should_stop=None) -> Simulation:
    """Put the paper image (and the primitive objects, if built) at sample ``index``; only what
    changed since the image was last shown is converted (see images.show_paper)."""
    st = checks.settings(scene)
    pb = playback_for(scene)
    sim = pb.seek(index, progress, should_stop)
    images.show_paper(images.ensure_paper_image(st), sim.paper, sim.index, pb.overlay)
    if primitives.primitive_objects(scene):
        primitives.sync_primitives(scene, sim, create=False)
    return sim


def show_frame(scene, frame: float) -> Simulation:
    pb = playback_for(scene)
    return show(scene, frames.samples_at_frame(pb.rec, scene, frame))
