# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.bake_cache: checkpoints of the simulation for a render farm.

Any worker opening the saved .blend renders any frame in bounded time: it loads the nearest
checkpoint at or before the frame and simulates on from there (sim.timeline), and the image is
exactly that of simulating straight to the frame. The checkpoints go next to the .blend, in
``hairy_brush_cache_<file name>/<scene>/``, as Blender's own caches do (``blendcache_``): a farm
that syncs the .blend's folder carries them along, and the .blend itself stays small (inside
it, every save and every worker's load would carry them). Each checkpoint holds only the paper
tiles changed since the previous one. They are made for one recording and its settings: any
change makes them stale (ignored until baked again). Every file carries the key, a new bake is
swapped in whole, and a cache that is not provably this scene's is ignored with a warning
(``sim.engine.checkpoints``, issue 30)."""

from __future__ import annotations

import bpy

from ..blender import checks, playback, recordings, runtime
from ..blender.jobs import Job, JobOperator, deadline
from ..sim.engine.checkpoints import save_checkpoints
from ..sim.engine.simulation import Simulation
from ..sim.engine.timeline import Timeline
from . import polls


class CacheJob(Job):
    """Simulate the whole recording on a timeline that keeps a checkpoint every
    playback.CACHE_EVERY samples, a slice at a time; the files are written at the end."""

    title = "Baking the farm cache"

    def __init__(self, scene):
        self.scene = scene
        self.folder = playback.cache_folder(scene)
        if self.folder is None:
            raise checks.UserError("Save the file first: the cache goes next to the .blend")
        self.key = playback.cache_key(scene)
        self.rec = recordings.recording_from_scene(scene)
        self.timeline = Timeline(Simulation(self.rec), playback.CACHE_EVERY, budget_bytes=2**62)

    def step(self, budget_s: float) -> bool:
        n = len(self.rec.samples)
        sim = self.timeline.seek(n, should_stop=deadline(budget_s))
        self.fraction = sim.index / max(n, 1)
        self.status = f"sample {sim.index} of {n}"
        return sim.index >= n

    def finish(self, context):
        save_checkpoints(self.timeline, self.folder, self.key)
        runtime.get().forget_playbacks()  # the next frame change reads the new checkpoints
        n = len(self.timeline.snaps)
        return "INFO", f"{n} checkpoints in {self.folder} ({self.timeline.nbytes / 2**20:.0f} MB)"


class HAIRY_BRUSH_OT_bake_cache(JobOperator, bpy.types.Operator):
    """Write checkpoints of the simulation next to the saved .blend, so that a render farm's
    workers render any frame in bounded time, in any order"""

    bl_idname = "hairy_brush.bake_cache"
    bl_label = "Bake Farm Cache"
    bl_options = {"REGISTER"}

    @classmethod
    def poll(cls, context):
        if not polls.recording(cls, context):
            return False
        if not bpy.data.filepath:
            cls.poll_message_set("Save the file first: the cache goes next to the .blend")
            return False
        return True

    def execute(self, context):
        try:
            job = CacheJob(context.scene)
        except (*checks.USER_ERRORS, MemoryError) as exc:
            return self._failed(exc)
        return self.run_job(context, job)
