# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on's runtime state, in one object: what it keeps between calls while Blender runs and
never saves (everything here can be rebuilt from the .blend). Created when the add-on registers,
cleared and dropped when it unregisters; ``get()`` returns it.

Nothing else in the add-on keeps module-level state: a cache lives here or nowhere."""

from __future__ import annotations

import contextlib
from dataclasses import dataclass, field
from typing import ClassVar


@dataclass
class Runtime:
    # the artwork at any frame (blender.playback): scene name -> its Playback; and scene name ->
    # (cache key, message) of a recording that failed to load, so it fails again at once
    playbacks: dict = field(default_factory=dict)
    failed: dict = field(default_factory=dict)
    # the pixels each paper image shows (blender.images): image pointer -> sim PaperView
    views: dict = field(default_factory=dict)
    # a mesh that is the paper (blender.surfaces): (object name, digest) -> sim Surface;
    # (digest, W, H, px/mm, width mm) -> SurfacePaper without frames; a mesh's cheap key -> its
    # digest while no mesh changed; surface digest -> ray caster (Blender's BVH tree)
    surfaces: dict = field(default_factory=dict)
    papers: dict = field(default_factory=dict)
    digests: dict = field(default_factory=dict)
    casters: dict = field(default_factory=dict)
    trust_digests: bool = False  # following frames: a kept digest holds (blender.surfaces)
    suspended: int = 0  # our own operators step frames: the frame handler does nothing
    last_error: str = ""  # the frame handler's last message (printed once, not on every frame)
    painter: object = None  # the live painting in progress (operators.paint), if any
    # what each cell of the last work written left on the paper (blender.work): its key (the
    # cell's own recording) -> sim.writing.work.compose.CellInk, so writing more simulates only
    # the new cells
    cell_inks: dict = field(default_factory=dict)
    # functions registered with bpy.app.timers (the frame handler's catch-up), persistent and
    # unregistered by clear() (a file loaded, the add-on disabled): none outlives the add-on
    # or its file, and Blender never frees one itself (Blender 4.2's bpy module crashes at exit
    # after it freed a Python timer, at a file load or at exit; not after unregister)
    timers: list = field(default_factory=list)

    current: ClassVar[Runtime | None] = None

    def clear(self):
        """Forget every cache (another file was loaded, or the add-on is going away)."""
        self.forget_playbacks()
        self.views.clear()
        self.forget_surfaces()
        self.cell_inks = {}
        self.last_error = ""
        self.painter = None
        self.stop_timers()

    def start_timer(self, fn, first_interval: float):
        """``bpy.app.timers.register(fn)``, kept so that ``clear`` can stop it."""
        import bpy

        self.timers = [f for f in self.timers if bpy.app.timers.is_registered(f)]
        self.timers.append(fn)
        bpy.app.timers.register(fn, first_interval=first_interval, persistent=True)

    def stop_timers(self):
        import bpy

        for fn in self.timers:
            if bpy.app.timers.is_registered(fn):
                bpy.app.timers.unregister(fn)
        self.timers.clear()

    def forget_playbacks(self):
        """The recording was replaced, or a cache baked: the next frame change starts again."""
        self.playbacks.clear()
        self.failed.clear()

    def forget_surfaces(self):
        """Meshes of another file, or changed: surfaces, papers, digests and rays again."""
        for d in (self.surfaces, self.papers, self.digests, self.casters):
            d.clear()

    @contextlib.contextmanager
    def frames_suspended(self):
        """Frame changes made by our own operators (baking samples) must not simulate."""
        self.suspended += 1
        try:
            yield
        finally:
            self.suspended -= 1


def cache_dir() -> str:
    """The extension's folder for what it can measure again (the brush's calibrated response):
    in Blender's user folder of this extension, not in the user's home (call it on Blender's
    thread)."""
    import bpy

    return bpy.utils.extension_path_user(__package__.rpartition(".")[0], path="cache", create=True)


def get() -> Runtime:
    """The add-on's runtime state (the add-on must be registered)."""
    rt = Runtime.current
    if rt is None:
        raise RuntimeError("Virtual Hairy Brush is not registered")
    return rt


def register():
    Runtime.current = Runtime()


def unregister():
    if Runtime.current is not None:
        Runtime.current.clear()
    Runtime.current = None
