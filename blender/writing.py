# SPDX-License-Identifier: GPL-3.0-or-later
"""Writing from stroke data into the scene (Write Character, Imitate Picture): the engine writes
in a worker (calibration, practice passes); at the end the paper is sized, the brush empty
keyframed, the recording stored and the writing shown. On a surface paper (issue 17) the writing
is laid on the surface around the point under the brush empty (``surfaces.SurfaceWriting``)."""

from __future__ import annotations

import math

import numpy as np

from ..sim.picture.imitate import read_picture, write_imitation
from ..sim.writing.brush_size import brush_for_char
from ..sim.writing.response import calibrate
from ..sim.writing.writer import auto_size_mm, write_character
from . import checks, images, jobs, keyframes, recordings, runtime, surfaces

READ_SHARE = 0.05  # of the progress bar when imitating a picture: reading it
WRITE_SHARE = 0.6  # of the progress bar on a surface: the flat writing (then laying it)


def _share(progress, lo: float, hi: float):
    """progress(fraction, *details) reported on the part [lo, hi] of the bar."""
    return lambda f, *details: progress(lo + (hi - lo) * f, *details)


class WriteJob(jobs.WorkerJob):
    """The writing itself (calibration, practice passes) in a worker; ``finish`` sizes the
    paper, keyframes the brush, stores the recording and shows the writing. On a surface the
    worker also lays the writing on it and simulates it there."""

    title = "Writing character"
    on_surface = None  # surfaces.SurfaceWriting when the paper is a surface (set by ``step``)

    def step(self, budget_s: float) -> bool:
        if self._thread is None and not self.finished:  # first, on Blender's thread
            st = checks.settings(self.scene)
            self.on_surface = (
                surfaces.SurfaceWriting(self.scene) if surfaces.is_surface(st) else None
            )
        return super().step(budget_s)

    fit_brush = False  # a size other than the brush's own written with the brush for it

    def __init__(self, scene, char: dict, size_mm: float, passes: int, fit_brush: bool = True):
        self._begin(scene, char, size_mm)
        self.fit_brush = fit_brush
        super().__init__(lambda progress: self._write(size_mm, passes, progress))

    def _begin(self, scene, char: dict | None, size_mm: float):
        """What the worker needs from Blender, read on Blender's thread."""
        st = checks.settings(scene)
        self.scene, self.char = scene, char
        self.template = recordings.settings_recording(scene)
        self.ppm = float(st.px_per_mm)
        self.cache_dir = runtime.cache_dir()
        if size_mm:
            self._check(size_mm)

    def _check(self, size_mm: float) -> float:
        """The size as the settings will hold it (single precision), checked for memory."""
        size = float(np.float32(checks.check_number(size_mm, "Size (mm)")))
        w = max(1, round(size * self.ppm))
        checks.check_paper_pixels(w, w)
        return size

    def _write(self, size_mm: float, passes: int, progress, im=None):
        progress(0.0, "calibrating the brush")
        response = calibrate(self.template, cache_dir=self.cache_dir)
        template = self.template
        if not size_mm:  # the size follows from the brush's response
            size_mm = auto_size_mm(self.char, response)
        elif self.fit_brush and (im is None or not self.piece):  # a brush for the size
            template, response = brush_for_char(
                template, response, self.char, size_mm, self.cache_dir
            )
        size = self._check(size_mm)
        flat = progress if self.on_surface is None else _share(progress, 0.0, WRITE_SHARE)
        if im is None:
            rec, _, sim = write_character(
                self.char,
                0,
                template,
                size_mm=size,
                response=response,
                passes=passes,
                progress=flat,
                px_per_mm=self.ppm,
            )
        else:  # a picture's strokes, written as ``sim imitate`` writes them
            rec, _, sim = write_imitation(
                im, template, 0, size, passes, flat, self.ppm, response, self.piece
            )
        if self.on_surface is not None:
            del sim  # the flat paper, before the surface's is simulated
            rec, sim = self.on_surface.lay(rec, size, _share(progress, WRITE_SHARE, 1.0))
        return size, rec, sim

    def describe(self, details) -> str:
        return details[0] if details else "practising the strokes"

    def finish(self, context):
        size, rec, sim = self.result
        scene = self.scene
        st = checks.settings(scene)
        if self.on_surface is None:
            st.paper_width_mm = st.paper_height_mm = size  # the paper plane follows
            rec = recordings.new_recording(
                scene, rec.samples, dips=recordings.following_ink(rec.dips), written=rec
            )
            last = keyframes.keyframe_samples(
                scene, st, rec.samples, rec.sample_rate_hz, scene.frame_start
            )
        else:  # laid on the surface (the texture keeps its size)
            mats = self.on_surface.matrices(st, rec)
            last = keyframes.keyframe_matrices(
                scene, st, mats, rec.sample_rate_hz, scene.frame_start
            )
            surfaces.keep_surface_paper(self.on_surface.digest, self.on_surface.paper)
            rec.dips = recordings.following_ink(rec.dips)  # written in the scene's ink
        scene.frame_end = math.ceil(last)
        recordings.store_recording(st, rec)
        runtime.get().forget_playbacks()
        images.show_paper(images.ensure_paper_image(st), sim.paper, len(rec.samples))
        return "INFO", (
            f"{len(self.char['medians'])} strokes, {len(rec.samples)} samples, "
            f"{len(rec.dips)} dips, {size:.0f} mm"
        )


class ImitateJob(WriteJob):
    """Read the picture, then write its strokes as WriteJob does, in one worker."""

    title = "Imitating picture"

    def __init__(
        self,
        scene,
        picture,
        name: str,
        size_mm: float,
        passes: int,
        detail: int,
        piece=False,
        fit_brush=True,
    ):
        self._begin(scene, None, size_mm)
        self.name, self.strokes, self.piece = name, 0, piece
        self.fit_brush = fit_brush
        self.picture = picture  # let go once read: a large picture is not kept while writing
        jobs.WorkerJob.__init__(
            self, lambda progress: self._imitate(detail, size_mm, passes, progress, piece)
        )

    def _imitate(self, detail: int, size_mm: float, passes: int, progress, piece):
        progress(0.0, "reading the picture")
        picture, self.picture = self.picture, None
        im = read_picture(picture, detail, self.name, piece=piece)
        del picture
        self.char, self.strokes = im.char, len(im.strokes)

        def writing(frac, *details):
            progress(READ_SHARE + (1.0 - READ_SHARE) * frac, *details)

        writing(0.0, f"{self.strokes} strokes read")
        return self._write(size_mm, passes, writing, im)

    def finish(self, context):
        level, message = super().finish(context)
        return level, f"{self.name}: {message}"
