# SPDX-License-Identifier: GPL-3.0-or-later
"""Glue between Blender data and the engine: scene settings -> Recording, object matrices ->
6-DOF samples, engine images -> image datablocks, engine surfaces -> NURBS surface objects.
The maths (units, poses, rays, frames) is in ``sim.placement``; here it meets Blender's data.
"""

from __future__ import annotations

import contextlib
import dataclasses
import hashlib
import json
import math
import os

import bpy
import numpy as np

from .sim import surface as surf
from .sim.core import placement
from .sim.core.jsonio import MAX_JSON_BYTES, parse_json
from .sim.core.params import (
    MAX_PAPER_PIXELS,
    MAX_PAPER_SIDE_PX,
    ParameterError,
    QualityParams,
    geometry_from_preset,
    load_preset,
)
from .sim.core.recording import Dip, Recording, RecordingError, from_dict
from .sim.engine.timeline import DEFAULT_BUDGET_BYTES as SNAPSHOT_BUDGET_BYTES
from .sim.paper import display

RECORDING_TEXT = "HairyBrush Recording"
PAPER_IMAGE = "HairyBrush Paper"
PRIMITIVE_COLLECTION = "HairyBrush Primitives"
PAPER_TAG = "hairy_brush_paper"
PAINTED_KEY = "painted_samples"  # in a recording's "blender" extra: samples painted live
SHOWN_TAG = "hairy_brush_shown"  # on the paper image: how many samples it shows
DENSITY_TAG = "hairy_brush_density"  # on the paper image: its ink density image (relief)
SAMPLES_TAG = "hairy_brush_samples"  # on a recording text: its samples and dips when stored
DIPS_TAG = "hairy_brush_dips"
PRIMITIVE_TAG = "hairy_brush_primitive"
SURFACE_TAG = "hairy_brush_surface"  # on a mesh that is the paper (setup(surface=True))
SURFACE_KEY = "surface"  # a recording's section of surface frames (see sim.surface)
MM = placement.MM
MAX_INT_PROPERTY = 2**31 - 1  # Blender's IntProperty holds 32 bits
# memory a paper pixel costs: the engine's buffers (ink 12, wetness 4, last step 4), the kept
# display pixels (16) and Blender's float image (16)
BYTES_PER_PIXEL = 52
# and on a surface (sim.surface.TexelTiles): a texel's owner triangle (4) and 3D point (12), built
# where the marks reach (building takes at most BUILD_CHUNK texels' temporaries at a time)
SURFACE_BYTES_PER_PIXEL = 16


class UserError(Exception):
    """A problem to report to the user with ``self.report({'ERROR'}, str(exc))``."""


# every problem an operator reports to the user as it is (each message names what is wrong)
USER_ERRORS = (UserError, RecordingError, ParameterError, surf.SurfaceError)


def settings(scene):
    return scene.hairy_brush


def _in_scene(st, obj) -> bool:
    """Whether ``obj`` is still in the settings' scene (a deleted object can linger in the
    file, unlinked, while a property still points at it)."""
    return st.id_data.objects.get(obj.name) == obj


def require_brush_and_paper(st):
    if st.brush_object is None or not _in_scene(st, st.brush_object):
        raise UserError("No brush empty in the scene: run Setup or pick one in the sidebar")
    if st.paper_object is None or not _in_scene(st, st.paper_object):
        raise UserError("No paper plane in the scene: run Setup or pick one in the sidebar")
    return st.brush_object, st.paper_object


# settings a hand-edited .blend could hold as NaN or infinity (Blender keeps them)
FINITE_SETTINGS = {
    "paper_width_mm": "Paper width",
    "paper_height_mm": "Paper height",
    "px_per_mm": "Resolution",
    "sample_rate_hz": "Sample rate",
    "dip_depth": "Dip depth",
    "dip_wetness": "Dip wetness",
    "paint_press_mm": "Press",
}


def check_settings(st):
    """One clear message for a setting that is not a number."""
    for name, label in FINITE_SETTINGS.items():
        if not math.isfinite(getattr(st, name)):
            raise UserError(f"{label} is not a number: set it again in the sidebar")
    for name in QualityParams.names():
        if not math.isfinite(getattr(st.quality, name)):
            raise UserError(f"Quality value '{name}' is not a number: set it again")


# ------------------------------------------------------------------------------ paper size
def paper_pixels(st) -> tuple[int, int]:
    w = max(1, int(round(st.paper_width_mm * st.px_per_mm)))
    h = max(1, int(round(st.paper_height_mm * st.px_per_mm)))
    return w, h


def check_paper_size(st) -> tuple[int, int]:
    check_settings(st)
    return check_paper_pixels(*paper_pixels(st))


def check_paper_pixels(w: int, h: int, extra_per_pixel: int = 0) -> tuple[int, int]:
    """UserError unless a paper of w x h px fits the engine's limits and the free memory
    (``extra_per_pixel``: what else a pixel costs, e.g. a surface's texel points)."""
    need = w * h * (BYTES_PER_PIXEL + extra_per_pixel) + SNAPSHOT_BUDGET_BYTES
    free = available_memory()
    if w > MAX_PAPER_SIDE_PX or h > MAX_PAPER_SIDE_PX or w * h > MAX_PAPER_PIXELS:
        raise UserError(
            f"Paper of {w} x {h} px is too large (at most {MAX_PAPER_SIDE_PX} px a side, about "
            f"{need / 2**20:.0f} MB of memory): lower Resolution or the paper size"
        )
    if free is not None and need > free:
        raise UserError(
            f"Paper of {w} x {h} px needs about {need / 2**20:.0f} MB of memory and "
            f"{free / 2**20:.0f} MB are free: lower Resolution or the paper size"
        )
    return w, h


def available_memory() -> int | None:
    """Bytes of physical memory free now (None where the system does not say)."""
    try:
        return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (AttributeError, ValueError, OSError):
        return None


# ------------------------------------------------------------------------------ transforms
def engine_to_paper_local(st) -> np.ndarray:
    """4x4: engine mm (paper corner origin) -> paper object's local metres (centred)."""
    return placement.engine_to_paper_local(st.paper_width_mm, st.paper_height_mm)


def engine_to_world(st, paper_obj) -> np.ndarray:
    return np.array(paper_obj.matrix_world) @ engine_to_paper_local(st)


def sample_from_matrices(st, brush_mw, paper_mw) -> np.ndarray:
    """One 6-DOF sample from the brush empty's and the paper's world matrices."""
    try:
        return placement.sample_from_matrices(
            brush_mw, paper_mw, st.paper_width_mm, st.paper_height_mm
        )
    except placement.PlacementError as exc:
        raise UserError(str(exc)) from None


def matrix_from_sample(st, paper_mw, sample) -> np.ndarray:
    """World matrix of the brush empty for a 6-DOF sample."""
    return placement.matrix_from_sample(paper_mw, sample, st.paper_width_mm, st.paper_height_mm)


# ------------------------------------------------------------------------------ recordings
def scene_overrides(st) -> dict:
    """The scene's settings as recording fields: they decide how a recording is rendered."""
    check_paper_size(st)
    paper = {
        "width_mm": float(st.paper_width_mm),
        "height_mm": float(st.paper_height_mm),
        "px_per_mm": float(st.px_per_mm),
        "preset": st.paper_preset,
    }
    paper["color"] = [float(c) for c in st.paper_color]
    paper["capacity"] = float(st.paper_capacity)
    paper["fibre"] = float(st.paper_fibre)
    return {
        "paper": paper,
        "brush": {"preset": st.brush_preset},
        "ink": {"preset": st.ink_preset},
        "quality": st.quality.as_dict(),
        "seed": scene_seed(st),
    }


def read_recording_dict(st) -> dict:
    text = st.recording
    if text is None:
        raise UserError("No recording yet: bake the brush's animation, paint, or import one")
    body = text.as_string()
    if len(body) > MAX_JSON_BYTES:
        raise UserError(f"Recording text '{text.name}' is too large ({len(body)} characters)")
    return parse_json(body, f"Recording text '{text.name}'", UserError)


def recording_from_scene(scene) -> Recording:
    """The stored recording, rendered with the scene's current settings (another preset, size
    or resolution re-renders the same strokes)."""
    st = settings(scene)
    d = read_recording_dict(st)
    if isinstance(d, dict):
        over = scene_overrides(st)
        if isinstance(d.get("brush"), dict):  # the recording's own geometry overrides stay
            over["brush"] = {**d["brush"], **over["brush"]}
        d.update(over)
    try:
        return from_dict(d)
    except RecordingError as exc:
        raise UserError(f"Recording '{st.recording.name}': {exc}") from None


def store_recording(st, rec: Recording) -> bpy.types.Text:
    text = st.recording
    if text is None:
        text = bpy.data.texts.new(RECORDING_TEXT)
        st.recording = text
    text.from_string(recording_text(rec))
    # counted here, so the sidebar shows them without reading the text
    text[SAMPLES_TAG] = len(rec.samples)
    text[DIPS_TAG] = len(rec.dips)
    return text


def recording_text(rec: Recording) -> str:
    """The recording's JSON with one sample (and one surface frame) a line: Blender's text
    editing is quadratic in a line's length, linear in the number of lines."""
    d = rec.to_dict()
    samples = d.pop("samples")
    section = d.pop(SURFACE_KEY, None)
    head = json.dumps(d, separators=(",", ":"))

    def lines(rows):
        return ",\n".join(json.dumps(row, separators=(",", ":")) for row in rows)

    tail = '"samples":[\n' + lines(samples) + "\n]"
    if isinstance(section, dict) and isinstance(section.get("frames"), list):
        rest = {k: v for k, v in section.items() if k != "frames"}
        open_ = json.dumps(rest, separators=(",", ":"))[:-1] + ("," if rest else "")
        tail += f',"{SURFACE_KEY}":' + open_ + '"frames":[\n' + lines(section["frames"]) + "\n]}"
    elif section is not None:
        tail += f',"{SURFACE_KEY}":' + json.dumps(section, separators=(",", ":"))
    return head[:-1] + ("," if d else "") + tail + "}"


def scene_seed(st) -> int:
    """The seed the scene simulates with: Seed, or an imported recording's larger one."""
    text = st.seed_of_recording
    return int(text) if text.isdigit() else int(st.seed)


def copy_settings_from_recording(st, rec: Recording):
    """After an import: show the recording's own settings in the sidebar. Everything is checked
    against what the settings can hold first, so a refused recording changes nothing."""
    values = {
        "paper_width_mm": rec.width_mm,
        "paper_height_mm": rec.height_mm,
        "px_per_mm": rec.px_per_mm,
        "seed": rec.seed % (MAX_INT_PROPERTY + 1),
        "sample_rate_hz": rec.sample_rate_hz,
        "brush_preset": rec.preset_name("brush"),
        "paper_preset": rec.preset_name("paper"),
        "ink_preset": rec.preset_name("ink"),
    }
    q, _geom, _paper, _ink = rec.resolve()
    _check_fits(st, "paper_capacity", _paper.capacity)
    _check_fits(st, "paper_fibre", _paper.fibre)
    quality = {name: getattr(q, name) for name in QualityParams.names()}
    for name, value in values.items():
        _check_fits(st, name, value)
    for name, value in quality.items():
        _check_fits(st.quality, name, value)
    for name, value in values.items():
        setattr(st, name, value)
    for name, value in quality.items():
        setattr(st.quality, name, value)
    st.paper_color, st.paper_capacity = _paper.color, _paper.capacity
    st.paper_fibre = _paper.fibre
    st.seed_of_recording = str(rec.seed) if rec.seed > MAX_INT_PROPERTY else ""


def _check_fits(group, name: str, value):
    """UserError unless ``value`` fits the property (its range, or its enum's items)."""
    prop = group.bl_rna.properties[name]
    if prop.type == "ENUM":
        if value not in {item.identifier for item in prop.enum_items}:
            kind = prop.name.lower().removesuffix(" preset")
            raise UserError(f"'{value}' is not a {kind} preset of this extension")
    elif not prop.hard_min <= value <= prop.hard_max:
        raise UserError(
            f"{prop.name} {value} is outside what the setting holds "
            f"({prop.hard_min:g} to {prop.hard_max:g})"
        )


def new_recording(scene, samples, dips=None) -> Recording:
    """A validated recording of ``samples`` at the scene's sample rate and settings, timed from
    the scene's first frame; raises UserError (bad settings) or RecordingError (bad samples)."""
    st = settings(scene)
    rec = Recording(np.asarray(samples, dtype=float), sample_rate_hz=float(st.sample_rate_hz))
    rec.dips = list(dips) if dips is not None else [current_dip(st, 0)]
    rec.extra["blender"] = {"frame_start": scene.frame_start}
    d = rec.to_dict()
    d.update(scene_overrides(st))
    return from_dict(d)


def settings_recording(scene) -> Recording:
    """A one-sample recording that carries only the scene's settings (brush, paper, ink,
    quality, rate, seed): the template from which the engine writes or fits."""
    return new_recording(scene, [[0.0, 0.0, 100.0, 0.0, 0.0, 0.0]])


def current_dip(st, before_sample: int) -> Dip:
    return Dip(before_sample, float(st.dip_depth), tuple(st.ink_color), float(st.dip_wetness))


# ------------------------------------------------------------------------------ surfaces
def is_surface(st) -> bool:
    """Whether the paper is a mesh made paper by setup(surface=True), not the flat plane."""
    obj = st.paper_object
    return obj is not None and SURFACE_TAG in obj


def surface_space(paper_obj) -> np.ndarray:
    """4x4: the surface's space (the paper object's axes and origin, metres, its scale applied
    to the mesh instead) -> world. The engine's surface is this space in millimetres."""
    m = np.array(paper_obj.matrix_world)
    m[:3, :3] /= np.maximum(np.linalg.norm(m[:3, :3], axis=0), 1e-30)
    return m


_SURFACES: dict = {}  # (object name, digest) -> sim.surface.Surface
_PAPERS: dict = {}  # (digest, W, H, px/mm, width mm) -> sim.surface.SurfacePaper without frames


def mesh_arrays(obj) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """(vertices in the surface's space in mm, triangles, UVs per triangle corner or None)."""
    me = obj.data
    me.calc_loop_triangles()
    co = np.empty(len(me.vertices) * 3)
    me.vertices.foreach_get("co", co)
    to_surface = np.linalg.inv(surface_space(obj)) @ np.array(obj.matrix_world)
    verts = (co.reshape(-1, 3) @ to_surface[:3, :3].T) * MM
    tris = np.empty(len(me.loop_triangles) * 3, np.int64)
    me.loop_triangles.foreach_get("vertices", tris)
    uv_layer = me.uv_layers.active
    if uv_layer is None:
        return verts, tris.reshape(-1, 3), None
    loops = np.empty(len(me.loop_triangles) * 3, np.int64)
    me.loop_triangles.foreach_get("loops", loops)
    uv = np.empty(len(me.loops) * 2)
    uv_layer.data.foreach_get("uv", uv)
    return verts, tris.reshape(-1, 3), uv.reshape(-1, 2)[loops].reshape(-1, 3, 2)


def _digest(verts, tris, uvs) -> str:
    h = hashlib.sha1(verts.tobytes(), usedforsecurity=False)
    h.update(tris.tobytes())
    h.update(b"-" if uvs is None else uvs.tobytes())
    return h.hexdigest()


def mesh_surface(obj) -> tuple[surf.Surface, str]:
    """The engine's surface of a mesh and a digest of it (kept until the mesh changes)."""
    verts, tris, uvs = mesh_arrays(obj)
    digest = _digest(verts, tris, uvs)
    key = (obj.name, digest)
    if key not in _SURFACES:
        _SURFACES.clear()
        _SURFACES[key] = surf.surface_from_arrays(verts, tris, uvs, f"Mesh '{obj.name}'")
    return _SURFACES[key], digest


_DIGESTS: dict = {}  # a mesh's cheap key -> its digest, while no mesh changed (frame changes)
_TRUST_DIGESTS = [False]


@contextlib.contextmanager
def trusting_digests():
    """Within it (following frames), surface_digest takes a kept digest of the paper mesh while
    its cheap key (name, datablock, sizes, matrices, UV map) holds and no mesh changed since
    (handlers.on_depsgraph_update forgets them): a frame change neither reads nor hashes the
    mesh. Elsewhere (operators) the mesh is read and hashed, and the digest kept."""
    old, _TRUST_DIGESTS[0] = _TRUST_DIGESTS[0], True
    try:
        yield
    finally:
        _TRUST_DIGESTS[0] = old


def forget_digests():
    """A mesh changed (or undo, or another file): digests are computed again."""
    _DIGESTS.clear()


def _cheap_mesh_key(obj) -> tuple:
    me, uv = obj.data, obj.data.uv_layers.active
    mats = np.r_[np.ravel(obj.matrix_world), np.ravel(surface_space(obj))]
    sizes = (len(me.vertices), len(me.loops), len(me.polygons))
    return (obj.name, me.as_pointer(), sizes, mats.tobytes(), uv.name if uv else None)


def surface_digest(st) -> str:
    """Changes whenever the surface the scene writes on changes ('' for the flat paper)."""
    if not is_surface(st):
        return ""
    key = _cheap_mesh_key(st.paper_object)
    if not _TRUST_DIGESTS[0] or key not in _DIGESTS:
        _DIGESTS.clear()
        _DIGESTS[key] = _digest(*mesh_arrays(st.paper_object))
    return _DIGESTS[key]


def surface_paper(st, rec: Recording):
    """The engine's SurfacePaper of the scene's surface for ``rec`` (None on flat paper)."""
    if not is_surface(st):
        return None
    surface, digest = mesh_surface(st.paper_object)
    frames = surf.frames_from_dict(rec.extra.get(SURFACE_KEY), len(rec.samples))
    if frames is None:
        raise UserError(
            f"The recording has no surface frames (it was made on flat paper): bake or paint "
            f"it again on '{st.paper_object.name}', or set up a flat paper to replay it"
        )
    return surface_paper_base(surface, digest, rec).with_frames(frames)


def surface_paper_base(surface, digest: str, rec: Recording, build: bool = True):
    """The SurfacePaper (no frames) of a surface at the recording's texture size and px/mm,
    kept for the session; None when it is not kept yet and ``build`` is False."""
    key = (digest, rec.width_px, rec.height_px, rec.px_per_mm, rec.width_mm)  # all it depends on
    if key not in _PAPERS:
        if not build:
            return None
        keep_surface_paper(
            digest,
            surf.SurfacePaper(
                surface, None, rec.width_px, rec.height_px, rec.px_per_mm, rec.width_mm
            ),
        )
    return _PAPERS[key]


def keep_surface_paper(digest: str, paper):
    """Keep a SurfacePaper built elsewhere (a worker) for the session."""
    _PAPERS.clear()
    _PAPERS[(digest, paper.W, paper.H, paper.ppm, paper.side_mm)] = paper


class SurfaceWriting:
    """Writing done on flat paper (Write Character, Imitate Picture) laid on the scene's surface
    (issue 17) around the point under the brush empty. Made on Blender's thread; ``lay`` is
    numpy only, so a worker runs it."""

    def __init__(self, scene):
        st = settings(scene)
        self.surface, self.digest = mesh_surface(st.paper_object)
        base, rot = surface_pose(st, st.brush_object.matrix_world)
        hit = surf.axis_hit(self.surface, base, rot, surface_caster(st))
        self.centre = np.array(surface_origin(st))  # the writing's centre: under the brush
        self.start = surf.start_frame(self.surface, hit, self.centre, rot[:, 0])
        self.template = settings_recording(scene)
        self.paper = surface_paper_base(self.surface, self.digest, self.template, build=False)

    def lay(self, flat: Recording, size_mm: float, progress=None):
        """(recording on the surface, its finished Simulation) of a recording written on a
        flat size_mm square: the samples moved so the square's centre is the chart's point
        under the brush, their frames followed over the surface from there (sim.surface.lay_on),
        the scene's settings (the texture keeps its size), simulated on the surface."""
        from .sim.core.recording import quantise
        from .sim.engine.simulation import Simulation

        samples = np.array(flat.samples, dtype=float)
        samples[:, :2] += self.centre - size_mm / 2
        samples = quantise(samples)
        reach = 10 * max(self.template.width_mm, self.template.height_mm)  # what a recording holds
        if np.abs(samples[:, :2]).max() > reach:
            raise UserError(
                f"A {size_mm:.0f} mm character is far larger than the surface it is laid on "
                f"(its texture covers {self.template.width_mm:.0f} mm a side): choose a smaller "
                "size"
            )

        def part(lo, hi, what):
            return None if progress is None else (lambda f: progress(lo + (hi - lo) * f, what))

        t = self.template
        if self.paper is None:  # its triangle grid also serves lay_on
            self.paper = surf.SurfacePaper(
                self.surface, None, t.width_px, t.height_px, t.px_per_mm, t.width_mm
            )
        near = self.paper.near
        frames = surf.lay_on(self.surface, self.start, samples, near, part(0, 0.3, "laying"))
        extra = {**self.template.extra, SURFACE_KEY: {"frames": frames.tolist()}}
        rec = dataclasses.replace(self.template, samples=samples, dips=list(flat.dips))
        rec.extra = extra
        sim = Simulation(rec, surface=self.paper.with_frames(frames))
        return rec, sim.run(progress=part(0.3, 1.0, "simulating on the surface"))

    def matrices(self, st, rec: Recording) -> list:
        """World matrices of the brush along the laid recording (its surface poses)."""
        frames = np.asarray(rec.extra[SURFACE_KEY]["frames"], dtype=float)
        return [surface_matrix(st, f, s) for f, s in zip(frames, rec.samples, strict=True)]


def surface_pose(st, mw) -> tuple[np.ndarray, np.ndarray]:
    """(base point in mm, rotation) of an object's world matrix in the surface's space."""
    rel = np.linalg.inv(surface_space(st.paper_object)) @ np.asarray(mw, dtype=float)
    rot = rel[:3, :3] / np.maximum(np.linalg.norm(rel[:3, :3], axis=0), 1e-30)
    return rel[:3, 3] * MM, rot


def surface_matrix(st, frame, sample) -> np.ndarray:
    """World matrix of the brush for a sample in a surface frame."""
    base, rot = surf.pose_from_sample(frame, sample)
    rel = np.eye(4)
    rel[:3, :3], rel[:3, 3] = rot, base / MM
    return surface_space(st.paper_object) @ rel


_CASTERS: dict = {}  # surface digest -> ray caster (Blender's BVH tree of its triangles)


def surface_caster(st):
    """``cast(origin, direction)`` in the surface's space (mm) -> its first sim.surface.Hit or
    None, through a BVH tree of the surface's triangles (sim.surface.ray_hit looks at every
    triangle: fine for tests, slow for a mesh of many thousands while painting or baking)."""
    from mathutils import Vector
    from mathutils.bvhtree import BVHTree

    surface, digest = mesh_surface(st.paper_object)
    if digest not in _CASTERS:
        _CASTERS.clear()
        tree = BVHTree.FromPolygons(surface.verts.tolist(), surface.tris.tolist())

        def cast(o, d):
            loc, _normal, index, dist = tree.ray_cast(Vector(o), Vector(d))
            if loc is None:
                return None
            if surface.face_normals[index] @ d > 0:
                # in through a crack (a ray along an edge can slip between faces in the
                # tree's single precision): the exact test over all triangles decides
                return surf.ray_hit(surface, o, d)
            return surf.hit_at(surface, index, loc, dist)

        _CASTERS[digest] = cast
    return _CASTERS[digest]


def surface_ray(st, origin, direction):
    """Where a world ray first meets the surface: the sim.surface.Hit, or None."""
    to_surface = np.linalg.inv(surface_space(st.paper_object))
    o = (to_surface @ np.r_[np.asarray(origin, dtype=float), 1.0])[:3] * MM
    d = to_surface[:3, :3] @ np.asarray(direction, dtype=float)
    return surface_caster(st)(o, d)


def surface_origin(st) -> tuple[float, float]:
    """The chart position a surface's first frame is developed from (see sim.surface)."""
    return float(st.paper_width_mm) / 2, float(st.paper_height_mm) / 2


def forget_surfaces():
    _DIGESTS.clear()
    _SURFACES.clear()
    _PAPERS.clear()
    _CASTERS.clear()


# ------------------------------------------------------------------------------ time
def timeline(rec: Recording, scene) -> tuple[float, float]:
    """(frame_start, frames per sample) of a recording in this scene's timeline."""
    b = rec.extra.get("blender", {}) if isinstance(rec.extra, dict) else {}
    fps = scene.render.fps / scene.render.fps_base
    start = float(b.get("frame_start", scene.frame_start))
    return start, fps / rec.sample_rate_hz


def samples_at_frame(rec: Recording, scene, frame: float) -> int:
    """How many samples have been written by the end of ``frame``."""
    return placement.samples_at_frame(len(rec.samples), *timeline(rec, scene), frame)


def first_sample_from_frame(rec: Recording, scene, frame: float) -> int:
    """Index of the first sample at or after ``frame``."""
    return placement.first_sample_from_frame(len(rec.samples), *timeline(rec, scene), frame)


# ------------------------------------------------------------------------------ images
def ensure_paper_image(st, color=(1.0, 1.0, 1.0)) -> bpy.types.Image:
    """The paper image, made (a float image: see sim.display) or resized to the paper."""
    w, h = check_paper_size(st)
    img = st.paper_image
    if img is None:
        img = bpy.data.images.new(PAPER_IMAGE, w, h, alpha=True, float_buffer=True)
        img.generated_color = (*display.encode(color, linear=True), 1.0)
        img[PAPER_TAG] = 1
        st.paper_image = img
    elif tuple(img.size) != (w, h):
        img.scale(w, h)
    return img


_VIEWS: dict[int, display.PaperView] = {}  # paper image (as_pointer) -> the pixels it shows


def forget_views():
    """After undo or loading a file, image buffers may no longer hold what was shown."""
    _VIEWS.clear()


def show_paper(img, paper, index: int):
    """Show ``paper`` in the image: only the tiles changed since the image was last shown from
    the same paper are converted, then the kept pixels go to Blender in one call. ``index`` (the
    samples simulated) is kept on the image, so undo can show exactly what was seen."""
    key = img.as_pointer()
    view = _VIEWS.get(key)
    if view is None or view.linear != img.is_float:
        view = _VIEWS[key] = display.PaperView(linear=img.is_float)
    view.refresh(paper)
    if tuple(img.size) != (paper.W, paper.H):
        img.scale(paper.W, paper.H)
    img.pixels.foreach_set(view.flat())
    img.update()
    img[SHOWN_TAG] = int(index)
    if density_read(img, tag_reliefs(img)):
        show_density(img, paper.ink)


def tag_reliefs(img) -> set:
    """Objects whose Displace modifier reads the paper image (or its density image) are
    evaluated again: new pixels alone do not move a relief's vertices. Returns the names of
    those of the two images that a relief reads."""
    images = {img.name, img.get(DENSITY_TAG)}
    read = set()
    for obj in bpy.data.objects:
        for mod in obj.modifiers if obj.type == "MESH" else ():
            tex = getattr(mod, "texture", None) if mod.type == "DISPLACE" else None
            if tex is not None and getattr(tex, "image", None) is not None:
                if tex.image.name in images:
                    obj.update_tag()
                    read.add(tex.image.name)
    return read


def density_read(img, read: set) -> bool:
    """Whether the paper image's density image is among the images reliefs read (``read``, from
    tag_reliefs): only then is it refreshed (a whole second image)."""
    name = img.get(DENSITY_TAG)
    return isinstance(name, str) and name in read


def density_image(img, create: bool = False):
    """The paper image's ink density image (a relief that follows the density reads it;
    None when there is none and ``create`` is False)."""
    name = img.get(DENSITY_TAG)
    dens = bpy.data.images.get(name) if isinstance(name, str) else None
    if dens is None and create:
        w, h = img.size
        dens = bpy.data.images.new(f"{img.name} Ink Density", w, h, float_buffer=True)
        dens.colorspace_settings.name = "Non-Color"  # read as it is: the density
        dens[PAPER_TAG] = 1  # packed on save with the paper
        img[DENSITY_TAG] = dens.name
    return dens


def density_of(ink) -> np.ndarray:
    """(H, W) the grey density an image shows of the engine's ``Paper.ink``."""
    return np.clip(ink.mean(axis=2, dtype=np.float32), 0.0, 1.0)


def show_density(img, ink=None):
    """Fill the paper image's density image: the mean of the ink's density (the engine's
    ``Paper.ink``, bottom row first; None: the blank paper), grey. Costs a whole image, so
    only a paper with a density relief has one."""
    dens = density_image(img)
    if dens is None:
        return
    w, h = img.size
    if ink is None:
        write_density(dens, np.zeros((h, w), np.float32))
    else:
        write_density(dens, density_of(ink))


def write_density(dens, density):
    """A density (H, W), bottom row first, into the density image, grey."""
    h, w = density.shape
    if tuple(dens.size) != (w, h):
        dens.scale(w, h)
    rgba = np.ones((h, w, 4), np.float32)
    rgba[..., :3] = density[..., None]
    dens.pixels.foreach_set(rgba.ravel())
    dens.update()


def density_from_image(st, img) -> np.ndarray:
    """The ink density (H, W) the paper image shows: 1 - visible / the paper's colour, the
    channels' mean (the inverse of ``Paper.rgb``, to the image's precision)."""
    paper = np.maximum(np.asarray(blank_color(st), np.float32), 1e-6)
    return np.clip(1.0 - image_rgb(img) / paper, 0.0, 1.0).mean(axis=2)


def show_blank(st):
    """The paper image as the blank paper of the scene's paper preset."""
    color = blank_color(st)
    img = ensure_paper_image(st, color)
    w, h = paper_pixels(st)
    blank = np.empty((h, w, 3), np.float32)
    blank[:] = color
    write_image(img, blank)
    img[SHOWN_TAG] = 0
    if density_read(img, tag_reliefs(img)):
        show_density(img)
    return img


def blank_color(st) -> tuple:
    """The blank paper's colour as the engine will simulate it."""
    return tuple(float(c) for c in st.paper_color)


def write_image(img, rgb_bottom_up: np.ndarray):
    """Engine RGB (H, W, 3), bottom row first (Blender's order) -> image pixels."""
    _VIEWS.pop(img.as_pointer(), None)
    h, w, _ = rgb_bottom_up.shape
    if tuple(img.size) != (w, h):
        img.scale(w, h)
    rgba = np.empty((h, w, 4), np.float32)
    rgba[..., :3] = display.encode(rgb_bottom_up, linear=img.is_float)
    rgba[..., 3] = 1.0
    img.pixels.foreach_set(rgba.ravel())
    img.update()


def image_rgb(img) -> np.ndarray:
    """The image's visible colour (H, W, 3), bottom row first, as the engine's ``Paper.rgb``."""
    a = np.empty(len(img.pixels), np.float32)
    img.pixels.foreach_get(a)
    rgb = a.reshape(img.size[1], img.size[0], 4)[..., :3]
    return display.linear_to_srgb(rgb).astype(np.float32) if img.is_float else rgb


def pack_image(img):
    """Keep the pixels inside the .blend (nothing in side files the user can lose): float
    images as OpenEXR (lossless), byte images as PNG. Done when the file is saved."""
    ext, fmt = (".exr", "OPEN_EXR") if img.is_float else (".png", "PNG")
    if not img.filepath_raw or not img.filepath_raw.endswith(ext):
        img.filepath_raw = f"//{img.name}{ext}"
    img.file_format = fmt
    img.pack()


# ------------------------------------------------------------------------------ NURBS objects
def hair_length(st) -> float:
    return geometry_from_preset(load_preset("brush", st.brush_preset)).hair_length_mm


def keyframe_samples(scene, st, samples, rate_hz: float, frame_start: float):
    """Keyframe the brush empty along 6-DOF samples (one key per sample, linear), so the
    writing plays, can be edited, and bakes back into the same samples."""
    paper_mw = st.paper_object.matrix_world
    mats = [matrix_from_sample(st, paper_mw, s) for s in samples]
    return keyframe_matrices(scene, st, mats, rate_hz, frame_start)


def keyframe_matrices(scene, st, mats, rate_hz: float, frame_start: float):
    """Keyframe the brush empty through world matrices, one a sample (linear); returns the
    last key's frame."""
    from mathutils import Matrix

    obj = st.brush_object
    obj.rotation_mode = "ZYX"
    fps = scene.render.fps / scene.render.fps_base
    frames = frame_start + np.arange(len(mats)) * fps / rate_hz
    if obj.parent is not None:
        parent = np.array(obj.parent.matrix_world) @ np.array(obj.matrix_parent_inverse)
    else:
        parent = np.eye(4)
    inv_parent = np.linalg.inv(parent)
    loc = np.empty((len(mats), 3))
    rot = np.empty((len(mats), 3))
    prev = None
    for i, m in enumerate(mats):
        basis = Matrix((inv_parent @ np.asarray(m)).tolist())
        t, q, _scale = basis.decompose()
        e = q.to_euler("ZYX", prev) if prev is not None else q.to_euler("ZYX")
        loc[i], rot[i], prev = t[:], e[:], e
    remove_fcurves(obj, ("location", "rotation_euler"))  # other animation stays
    for path in ("location", "rotation_euler"):
        for k in range(3):
            obj.keyframe_insert(path, index=k, frame=float(frames[0]))
    curves = {(fc.data_path, fc.array_index): fc for fc in fcurves(obj.animation_data)}
    for path, values in (("location", loc), ("rotation_euler", rot)):
        for k in range(3):
            fc = curves[(path, k)]
            kp = fc.keyframe_points
            kp.add(len(mats) - len(kp))
            co = np.stack([frames, values[:, k]], axis=1).astype(np.float32)
            kp.foreach_set("co", co.ravel())
            for p in kp:
                p.interpolation = "LINEAR"
            fc.update()
    return float(frames[-1])


def remove_fcurves(obj, paths):
    """Delete the object's F-curves of these data paths (every index), keeping the rest."""
    ad = obj.animation_data
    if ad is None or ad.action is None:
        return
    action = ad.action
    if hasattr(action, "fcurves"):  # Blender < 5 (legacy actions)
        owners = [action.fcurves]
    else:
        slot = getattr(ad, "action_slot", None)
        owners = [
            bag.fcurves
            for layer in action.layers
            for strip in layer.strips
            if slot is not None and (bag := strip.channelbag(slot)) is not None
        ]
    for fcurves in owners:
        for fc in [fc for fc in fcurves if fc.data_path in paths]:
            fcurves.remove(fc)


def fcurves(ad):
    """The F-curves of an object's animation (legacy or slotted actions)."""
    action = ad.action
    if hasattr(action, "fcurves"):  # Blender < 5 (legacy actions)
        return list(action.fcurves)
    out = []
    slot = getattr(ad, "action_slot", None)
    for layer in action.layers:  # slotted actions (Blender 4.4+)
        for strip in layer.strips:
            bag = strip.channelbag(slot) if slot is not None else None
            if bag is not None:
                out.extend(bag.fcurves)
    return out
