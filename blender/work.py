# SPDX-License-Identifier: GPL-3.0-or-later
"""A work written from text into the scene (issue 27; the engine's sim.writing.work): Write
Text lays a new work out on the paper or goes on after its last character, Sign and Seal signs
it, Write Cell Again writes one of its cells anew with another seed.

The engine writes in a worker (calibration, the cells, the paper): a job changes the scene only
when it finishes, so Esc leaves nothing of a call. Then the recording is stored (its work - the
layout, every cell's samples - is in it, so the next call goes on from it), the brush empty is
keyed for the new samples only (the keys of every other sample stay as they are; a cell written
again that takes longer moves the later keys by as much), and the paper image shows the work
with its grid and seal as ``sim render`` draws them. On flat paper the paper is put together
from its cells, each simulated alone (``compose.render``; bit for bit the one run of the
recording), and the cells simulated before are kept (``runtime.cell_inks``), so a call
simulates only the cells it wrote.

On a surface paper the work is laid out in the texture's UV space the same way (its mm are the
texture's: UV = mm / the paper's size): each cell is laid on the surface around the point whose
UV is its centre, upright along the texture's x there (``SurfaceWork``), its frames followed
over the surface from that point, so a cell's frames depend on nothing but the cell; the work
is then simulated on the surface."""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass, replace

import numpy as np

from ..sim import surface as surf
from ..sim.core.params import ParameterError
from ..sim.engine.simulation import Simulation
from ..sim.writing.hanzi import lookup
from ..sim.writing.response import calibrate
from ..sim.writing.work import compose, edit
from ..sim.writing.work.layout import Layout, Settings, lay_out, sign
from ..sim.writing.work.text import (
    CHAR,
    Glyph,
    MissingCharacters,
    describe,
    drop,
    missing_characters,
    parse_text,
)
from . import (
    checks,
    frames,
    images,
    jobs,
    keyframes,
    playback,
    recordings,
    runtime,
    surfaces,
    transforms,
)

WRITE_SHARE = 0.7  # of the progress bar: writing the cells (then the paper)
CHAR_MM_STEP = 0.5  # a size fitted to the paper is rounded down to this


# ------------------------------------------------------------------------------ the settings
@dataclass(frozen=True)
class Choices:
    """What the sidebar's Write Text settings say, read on Blender's thread."""

    direction: str
    per_line: int | None
    char_mm: float | None
    grid: str
    options: compose.Options
    punctuation: str
    skip_missing: bool
    data: str | None
    signature: str = ""  # the sidebar's, which a new work of size 0 leaves room for
    seal: str = ""


def choices(st) -> Choices:
    """The scene's Write Text settings (UserError for a size that is not a number)."""
    import bpy

    w = st.work
    checks.check_number(w.char_mm, "Write Text's Size", "set it again in the sidebar")
    checks.check_number(w.variation, "Write Text's Variation", "set it again in the sidebar")
    data = bpy.path.abspath(w.data_path) if w.data_path.strip() else None
    return Choices(
        w.direction,
        w.per_line or None,
        float(w.char_mm) or None,
        w.grid,
        compose.Options(int(w.passes), None, float(w.variation), bool(w.fit_brush)),
        w.punctuation,
        bool(w.skip_missing),
        data,
        w.signature,
        w.seal,
    )


def missing_message(exc: MissingCharacters) -> str:
    """The engine's message for characters without stroke data, in the sidebar's words."""
    names = ", ".join(describe(c) for c in exc.chars)
    return (
        f"No stroke data for {len(exc.chars)} character(s): {names}. Nothing was written: "
        "remove them, turn on Skip Missing, or choose Stroke Data that has them"
    )


def user_error(exc: Exception) -> checks.UserError:
    if isinstance(exc, MissingCharacters):
        return checks.UserError(missing_message(exc))
    return checks.UserError(str(exc))


def scene_work(scene):
    """(the scene's recording, its Layout) when the recording holds a work; (None, None) when
    there is no recording; UserError for a recording that is not a work."""
    st = checks.settings(scene)
    if st.recording is None:
        return None, None
    rec = recordings.recording_from_scene(scene)
    work = compose.work_of(rec)
    if work is None:
        raise checks.UserError(
            f"Recording '{st.recording.name}' is not a work written with Write Text (it was "
            "painted, baked or written with Write Character): clear the Recording field "
            "(Animation > Recording) to start a work on an empty recording"
        )
    compose.check_work(rec)
    if surfaces.is_surface(st) and recordings.SURFACE_KEY not in rec.extra:
        raise checks.UserError(
            f"The work was written on flat paper: write it on '{st.paper_object.name}' from "
            "an empty recording, or set up a flat paper to go on with it"
        )
    return rec, Layout.from_dict(work["layout"])


# -------------------------------------------------------------------------------- checking
def check_new(text: str, ch: Choices, paper_mm) -> None:
    """A new work's text and layout checked before anything is written (ParameterError,
    MissingCharacters); a size of 0 is chosen later, from the brush."""
    settings = _settings(ch, paper_mm)
    lines, settings, _ = compose.prepare(
        text, settings, data=ch.data, punctuation=ch.punctuation, skip_missing=ch.skip_missing
    )
    if settings.char_mm is not None:
        lay_out(lines, settings)


def check_append(rec, lay: Layout, text: str, ch: Choices, new_line: bool) -> None:
    """Text to go on a work, checked as append_text checks it before writing."""
    if lay.seal or any(c.role != "text" for c in lay.cells):
        raise ParameterError("The work is signed: no text goes after its signature and seal")
    lines = parse_text(text, ch.punctuation)
    missing = missing_characters(lines, ch.data)
    if missing and not ch.skip_missing:
        raise MissingCharacters(missing, ch.data)
    if not edit.place_text(Layout.from_dict(lay.to_dict()), drop(lines, missing), new_line):
        raise ParameterError("The text has nothing to write (only spaces and punctuation?)")


def check_sign(lay: Layout, signature: str, seal: str, style: str, data) -> None:
    sig, seal = compose._glyphs_of(signature), compose._glyphs_of(seal)
    if not (sig or seal):
        raise ParameterError("Type a signature or a seal first")
    missing = missing_characters([[Glyph(c, CHAR) for c in sig + seal]], data)
    if missing:
        raise MissingCharacters(missing, data)
    sign(Layout.from_dict(lay.to_dict()), sig, seal, style)  # on a copy: it fits the paper


def _settings(ch: Choices, paper_mm) -> Settings:
    return Settings(
        direction=ch.direction,
        per_line=ch.per_line,
        grid=ch.grid,
        char_mm=ch.char_mm,
        paper_mm=tuple(paper_mm),
    )


def fitting_size(text: str, ch: Choices, paper_mm, response) -> float:
    """The size of a new work when Size is 0: the brush's own size for its characters
    (compose.natural_size_mm), smaller when the text would not fit the paper at it with room
    for the sidebar's signature and seal (signed later)."""
    settings = replace(_settings(ch, paper_mm), signature=ch.signature, seal=ch.seal)
    lines, settings, _ = compose.prepare(
        text, settings, data=ch.data, punctuation=ch.punctuation, skip_missing=True
    )
    chars = sorted({g.text for line in lines for g in line if g.kind == CHAR})
    size = compose.natural_size_mm([lookup(c, ch.data) for c in chars], response)
    fitted = lay_out(lines, replace(settings, char_mm=None)).char_mm
    return min(size, math.floor(fitted / CHAR_MM_STEP) * CHAR_MM_STEP)


# ------------------------------------------------------------------------------ the worker
def progress_mapper(progress, lo: float, hi: float, what: str):
    """A mapper (sim.writing.work) that writes the tasks one after another on the worker,
    telling ``progress`` before each (where Esc stops the job: between cells)."""

    def mapper(fn, tasks, done=None):
        out = []
        for k, task in enumerate(tasks):
            progress(lo + (hi - lo) * k / max(len(tasks), 1), f"{what} {k + 1} of {len(tasks)}")
            out.append(fn(task))
            if done is not None:
                done(k + 1, len(tasks))
        return out

    return mapper


def cell_key(sub) -> str:
    """What a cell's ink depends on: its own recording (compose.cell_recording) - samples,
    dips and every setting."""
    h = hashlib.sha1(np.ascontiguousarray(sub.samples).tobytes(), usedforsecurity=False)
    head = replace(sub, samples=np.zeros((1, 6))).to_dict()
    h.update(json.dumps(head, sort_keys=True).encode("utf-8"))
    return h.hexdigest()


def kept_mapper(kept: dict, fresh: dict, progress, lo: float, hi: float):
    """A mapper for compose.render's cells: a cell simulated before (``kept``, by cell_key) is
    taken as it was; every cell's ink goes into ``fresh``."""

    def mapper(fn, subs, done=None):
        out = []
        for k, sub in enumerate(subs):
            key = cell_key(sub)
            ink = kept.get(key)
            if ink is None:
                progress(lo + (hi - lo) * k / max(len(subs), 1), "simulating the paper")
                ink = fn(sub)
            fresh[key] = ink
            out.append(ink)
        return out

    return mapper


def cells_cover(rec, lay: Layout) -> bool:
    """Whether the cells' samples are the whole recording (nothing painted between them): then
    the paper can be put together from the cells."""
    spans = sorted(c.samples for c in lay.cells)
    at = 0
    for a, b in spans:
        if a != at:
            return False
        at = b
    return at == len(rec.samples)


@dataclass
class Change:
    """What a call did to the recording: the new recording; the first sample it wrote and how
    many; where the old recording's untouched tail began (its samples now ``shift`` later)."""

    rec: object
    first: int
    count: int
    end: int
    shift: int
    message: str


class WorkJob(jobs.WorkerJob):
    """Write, sign or rewrite in a worker (``edit(template, response, mapper)`` -> Change;
    ``old``: the scene's work before, None for a new one); on a surface the new samples are
    laid on it; the paper is simulated. ``finish`` stores the recording, keys the brush for
    the new samples and shows the paper."""

    title = "Writing text"

    def __init__(self, scene, old, edit_fn):
        st = checks.settings(scene)
        self.scene, self.old = scene, old
        # the scene's settings; a work written on keeps its brush's size (sim.writing.brush_size)
        self.template = recordings.with_brush_scale(recordings.settings_recording(scene), old)
        self.cache_dir = runtime.cache_dir()
        self.kept = runtime.get().cell_inks  # read by the worker, replaced in finish
        self.fresh = {}
        self.on_surface = SurfaceWork(scene) if surfaces.is_surface(st) else None
        self._edit = edit_fn
        super().__init__(self._work)

    def describe(self, details) -> str:
        return details[0] if details else "writing"

    def _work(self, progress):
        progress(0.0, "calibrating the brush")
        response = calibrate(self.template, cache_dir=self.cache_dir)
        share = WRITE_SHARE if self.on_surface is None else 0.5
        mapper = progress_mapper(progress, 0.0, share, "writing cell")
        change = self._edit(self.template, response, mapper)
        if self.on_surface is not None:
            rec = change.rec = self.on_surface.lay(self.old, change)
            progress(0.6, "simulating on the surface")
            sim = Simulation(rec, surface=self.on_surface.paper.with_frames(frames_of(rec)))
            sim.run(progress=lambda f: progress(0.6 + 0.4 * f, "simulating on the surface"))
            return change, sim.paper
        extra = {k: v for k, v in change.rec.extra.items() if k != recordings.SURFACE_KEY}
        rec = change.rec = replace(change.rec, extra=extra)  # flat: no surface frames
        lay = Layout.from_dict(compose.work_of(rec)["layout"])
        if cells_cover(rec, lay):
            mapper = kept_mapper(self.kept, self.fresh, progress, share, 1.0)
            try:
                return change, compose.render(rec, mapper=mapper)[0]
            except ParameterError:  # a cell's restarting dip replaced (Dip Brush at its start)
                self.fresh.clear()
        # strokes painted between the cells, or a cell that depends on the one before: the
        # whole run of the recording
        sim = Simulation(rec).run(progress=lambda f: progress(share + (1 - share) * f))
        return change, sim.paper

    def finish(self, context):
        change, paper = self.result
        scene, rec = self.scene, change.rec
        st = checks.settings(scene)
        start, _ = frames.timeline(rec, scene)
        new = rec.samples[change.first : change.first + change.count]
        if self.on_surface is None:
            paper_mw = st.paper_object.matrix_world
            mats = [transforms.matrix_from_sample(st, paper_mw, s) for s in new]
        else:
            fr = frames_of(rec)[change.first : change.first + change.count]
            mats = [surfaces.surface_matrix(st, f, s) for f, s in zip(fr, new, strict=True)]
            surfaces.keep_surface_paper(self.on_surface.digest, self.on_surface.paper)
        if self.old is None:  # a new work: the brush's keys are the work's (Write Character's)
            keyframes.keyframe_matrices(scene, st, mats, rec.sample_rate_hz, start)
        else:
            keyframes.splice_keyframes(
                scene, st, mats, rec.sample_rate_hz, start, change.first, change.end, change.shift
            )
        last = keyframes.key_frames(scene, rec.sample_rate_hz, start, len(rec.samples) - 1)
        scene.frame_end = math.ceil(float(last))
        recordings.store_recording(st, rec)
        rt = runtime.get()
        rt.forget_playbacks()
        if self.on_surface is None and self.fresh:
            rt.cell_inks = self.fresh  # the cells of this work, for the next call
        img = images.ensure_paper_image(st)
        over = playback.work_overlay(rec, paper)
        images.show_paper(img, paper, len(rec.samples), over, whole=self.on_surface is None)
        return "INFO", change.message


def frames_of(rec) -> np.ndarray:
    return np.asarray(rec.extra[recordings.SURFACE_KEY]["frames"], dtype=float)


# --------------------------------------------------------------------------- the three calls
def write_job(scene, text: str, new_line: bool) -> WorkJob:
    """Write Text: a new work on an empty recording, else the text after the work's last
    character. Everything that can be checked before writing is (UserError)."""
    st = checks.settings(scene)
    ch = choices(st)
    old, lay = scene_work(scene)
    paper_mm = (float(st.paper_width_mm), float(st.paper_height_mm))
    try:
        if old is None:
            check_new(text, ch, paper_mm)
        else:
            check_append(old, lay, text, ch, new_line)
    except ParameterError as exc:
        raise user_error(exc) from None
    ppm = float(st.px_per_mm)

    cache = runtime.cache_dir()  # (on Blender's thread)

    def new_work(template, response, mapper):
        settings = _settings(ch, paper_mm)
        if settings.char_mm is None:
            settings = replace(settings, char_mm=fitting_size(text, ch, paper_mm, response))
        rec, lay, skipped = compose.compose(
            text,
            settings,
            template,
            px_per_mm=ppm,
            data=ch.data,
            punctuation=ch.punctuation,
            skip_missing=ch.skip_missing,
            options=ch.options,
            mapper=mapper,
            response=response,
            cache_dir=cache,
        )
        return Change(rec, 0, len(rec.samples), 0, 0, _wrote(lay.cells, lay, skipped, rec))

    def append(_template, response, mapper):
        rec, cells = edit.append_text(
            old,
            text,
            data=ch.data,
            punctuation=ch.punctuation,
            skip_missing=ch.skip_missing,
            new_line=new_line,
            options=ch.options,
            mapper=mapper,
            response=response,
        )
        n = len(old.samples)
        lay_new = Layout.from_dict(compose.work_of(rec)["layout"])
        skipped = missing_characters(parse_text(text, ch.punctuation), ch.data)
        return Change(rec, n, len(rec.samples) - n, n, 0, _wrote(cells, lay_new, skipped, rec))

    return WorkJob(scene, old, new_work if old is None else append)


def _wrote(cells, lay: Layout, skipped, rec) -> str:
    chars = "".join(c.char for c in cells)
    text = f"Wrote {chars} ({len(cells)} cells, {lay.char_mm:.1f} mm); the work has "
    text += f"{len(lay.cells)} cells, {len(rec.samples)} samples"
    if skipped:
        text += f"; skipped (no stroke data): {', '.join(describe(c) for c in skipped)}"
    return text


def sign_job(scene, signature: str, seal: str, style: str) -> WorkJob:
    """Sign and Seal: the signature after the work's text and the seal after it."""
    st = checks.settings(scene)
    ch = choices(st)
    old, lay = scene_work(scene)
    if old is None:
        raise checks.UserError("No work to sign yet: write its text with Write Text first")
    try:
        check_sign(lay, signature, seal, style, ch.data)
    except ParameterError as exc:
        raise user_error(exc) from None

    def signed(_template, response, mapper):
        rec = edit.sign_work(
            old,
            signature,
            seal,
            style,
            data=ch.data,
            options=ch.options,
            mapper=mapper,
            response=response,
        )
        n = len(old.samples)
        what = " and ".join(x for x in (signature and "signed", seal and "sealed") if x)
        return Change(rec, n, len(rec.samples) - n, n, 0, f"The work is {what}")

    return WorkJob(scene, old, signed)


def rewrite_job(scene, index: int, seed: int | None) -> WorkJob:
    """Write Cell Again: cell ``index`` (writing order) written with another seed."""
    st = checks.settings(scene)
    ch = choices(st)
    old, lay = scene_work(scene)
    if old is None:
        raise checks.UserError("No work yet: write its text with Write Text first")
    if not 0 <= index < len(lay.cells):
        raise checks.UserError(f"No cell {index + 1}: the work has {len(lay.cells)} cells")
    a, b = lay.cells[index].samples

    def rewritten(_template, response, mapper):
        rec = edit.rewrite_cell(
            old, index, seed, data=ch.data, options=ch.options, mapper=mapper, response=response
        )
        cell = Layout.from_dict(compose.work_of(rec)["layout"]).cells[index]
        shift = (cell.samples[1] - cell.samples[0]) - (b - a)
        message = f"Cell {index + 1} ({cell.char}) written again with seed {cell.seed}"
        return Change(rec, a, b - a + shift, b, shift, message)

    return WorkJob(scene, old, rewritten)


# ------------------------------------------------------------------------------ the cursor
def cell_at(scene, lay: Layout, world_point) -> int | None:
    """The index of the cell whose place (its em box and half the gap around it) holds the
    point of the paper nearest ``world_point`` (the 3D cursor); None when none does."""
    st = checks.settings(scene)
    if surfaces.is_surface(st):
        surface, _ = surfaces.mesh_surface(st.paper_object)
        inv = np.linalg.inv(surfaces.surface_space(st.paper_object))
        p = (inv @ np.r_[np.asarray(world_point, dtype=float), 1.0])[:3] * transforms.MM
        hit = surf.closest_point(surface, p)
        u, v = hit.bary @ surface.uvs[hit.tri]
        x, y = u * float(st.paper_width_mm), v * float(st.paper_height_mm)
    else:
        inv = np.linalg.inv(transforms.engine_to_world(st, st.paper_object))
        x, y = (inv @ np.r_[np.asarray(world_point, dtype=float), 1.0])[:2]
    for k, c in enumerate(lay.cells):
        x0, y0, x1, y1 = c.territory(lay.vertical)
        if x0 <= x <= x1 and y0 <= y <= y1:
            return k
    return None


# ----------------------------------------------------------------------------- the surface
class SurfaceWork:
    """A work laid out in a surface's UV space (its mm are the texture's, UV = mm / the
    paper's size). Made on Blender's thread; ``lay`` is numpy only, so a worker runs it."""

    def __init__(self, scene):
        st = checks.settings(scene)
        self.surface, self.digest = surfaces.mesh_surface(st.paper_object)
        self.template = recordings.settings_recording(scene)
        self.paper = surfaces.surface_paper_base(
            self.surface, self.digest, self.template, build=False
        )

    def lay(self, old, change: Change):
        """The recording with frames: the old recording's kept, those of the samples the call
        wrote laid cell by cell (``cell_frames``)."""
        t = self.template
        if self.paper is None:
            self.paper = surf.SurfacePaper(
                self.surface, None, t.width_px, t.height_px, t.px_per_mm, t.width_mm
            )
        rec = change.rec
        lay = Layout.from_dict(compose.work_of(rec)["layout"])
        a, b = change.first, change.first + change.count
        parts = [frames_of(old)[: change.first]] if old is not None else []
        for cell in sorted(lay.cells, key=lambda c: c.samples):
            ca, cb = cell.samples
            if ca >= a and cb <= b and cb > ca:
                parts.append(self.cell_frames(rec, cell, lay))
        if old is not None:
            parts.append(frames_of(old)[change.end :])
        laid = np.concatenate(parts) if parts else np.zeros((0, surf.FRAME_WIDTH))
        if len(laid) != len(rec.samples):  # the call wrote whole cells: never seen
            raise checks.UserError("The work's cells do not cover the samples written")
        section = {"frames": laid.tolist()}
        return replace(rec, extra={**rec.extra, recordings.SURFACE_KEY: section})

    def cell_frames(self, rec, cell, lay: Layout) -> np.ndarray:
        """The frames of a cell's samples: from the surface point whose UV is the cell's
        centre, the texture's x the tangent there (the character upright in the texture),
        followed over the surface to each sample; the samples before the writing (the hand
        coming from the last cell) are followed backwards from that point, so the frames
        depend on the cell alone."""
        x0, y0, x1, y1 = cell.box()
        cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
        hit = surf.uv_hit(self.surface, (cx / rec.width_mm, cy / rec.height_mm))
        if hit is None:
            raise checks.UserError(
                f"Cell {cell.char!r} falls where the mesh's UV map has no face (texture at "
                f"{cx:.0f}, {cy:.0f} mm): a smaller size, another layout, or UVs that cover "
                "the texture"
            )
        du, _ = surf.uv_axes(self.surface, hit.tri)
        start = surf.start_frame(self.surface, hit, (cx, cy), du)
        a, b = cell.samples
        s = rec.samples[a:b]
        tx0, ty0, tx1, ty1 = cell.territory(lay.vertical)
        inside = (s[:, 0] >= tx0) & (s[:, 0] <= tx1) & (s[:, 1] >= ty0) & (s[:, 1] <= ty1)
        i0 = int(np.argmax(inside)) if inside.any() else 0
        near = self.paper.near
        ahead = surf.lay_on(self.surface, start, s[i0:], near)
        if i0 == 0:
            return ahead
        behind = surf.lay_on(self.surface, start, s[:i0][::-1], near)[::-1]
        return np.concatenate([behind, ahead])
