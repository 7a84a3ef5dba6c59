# SPDX-License-Identifier: GPL-3.0-or-later
"""The recording kept in the .blend (a text datablock of JSON): read with the scene's current
settings, stored one sample a line, made from samples, and its settings shown in the sidebar
after an import."""

from __future__ import annotations

import json
from dataclasses import replace

import bpy
import numpy as np

from ..sim.core.jsonio import MAX_JSON_BYTES, parse_json
from ..sim.core.params import QualityParams
from ..sim.core.recording import (
    Dip,
    Recording,
    RecordingError,
    brush_scale,
    from_dict,
    quantise,
)
from ..sim.writing.work.compose import WORK_KEY
from . import checks

RECORDING_TEXT = "HairyBrush Recording"
PAINTED_KEY = "painted_samples"  # in a recording's "blender" extra: samples painted live
SAMPLES_TAG = "hairy_brush_samples"  # on a recording text: its samples and dips when stored
DIPS_TAG = "hairy_brush_dips"
OWN_COLOR_TAG = "hairy_brush_own_colour_dips"  # and how many dips keep their own colour
SCALE_TAG = "hairy_brush_scale"  # the brush's size for the writing (sim.writing.brush_size)
HAIR_TAG = "hairy_brush_hair_mm"  # and the hair length of the brush it was recorded with
SURFACE_KEY = "surface"  # a recording's section of surface frames (see sim.surface)
WORK_TAG = "hairy_brush_work"  # on a recording text: its work's cells' characters (Write Text)
SIGNED_TAG = "hairy_brush_work_signed"  # and whether the work is signed or sealed


def scene_overrides(st) -> dict:
    """The scene's settings as recording fields: they decide how a recording is rendered."""
    checks.check_paper_size(st)
    paper = {
        "width_mm": float(st.paper_width_mm),
        "height_mm": float(st.paper_height_mm),
        "px_per_mm": float(st.px_per_mm),
        "preset": st.paper_preset,
    }
    paper["color"] = [float(c) for c in st.paper_color]
    paper["capacity"] = float(st.paper_capacity)
    paper["fibre"] = float(st.paper_fibre)
    paper["texture"] = float(st.paper_texture)
    return {
        "paper": paper,
        "brush": {"preset": st.brush_preset},
        # Ink Colour: what every dip that follows the ink loads (see sim.core.recording.Dip)
        "ink": {"preset": st.ink_preset, "color": [float(c) for c in st.ink_color]},
        "quality": checks.quality_values(st),
        "seed": scene_seed(st),
    }


def read_recording_dict(st) -> dict:
    text = st.recording
    if text is None:
        raise checks.UserError("No recording yet: bake the brush's animation, paint, or import one")
    body = text.as_string()
    if len(body) > MAX_JSON_BYTES:
        raise checks.UserError(
            f"Recording text '{text.name}' is too large ({len(body)} characters)"
        )
    return parse_json(body, f"Recording text '{text.name}'", checks.UserError)


def recording_from_scene(scene) -> Recording:
    """The stored recording, rendered with the scene's current settings (another preset, size
    or resolution re-renders the same strokes). With a brush of another hair length than the
    one it was recorded with, its samples are re-placed (see ``hair_shift``)."""
    st = checks.settings(scene)
    d = read_recording_dict(st)
    recorded = None
    if isinstance(d, dict):
        recorded = d.get("brush") if isinstance(d.get("brush"), dict) else {}
        over = scene_overrides(st)
        over["brush"] = {**recorded, **over["brush"]}  # its own geometry overrides stay
        d.update(over)
    try:
        rec = from_dict(d)
    except RecordingError as exc:
        raise checks.UserError(f"Recording '{st.recording.name}': {exc}") from None
    shift = hair_shift(recorded, rec) if recorded is not None else 0.0
    if shift:  # as a stored recording holds them, so what is painted on replays bit for bit
        rec.samples[:, 2] = quantise(rec.samples[:, 2] + shift)
    return rec


def hair_length_of(brush: dict) -> float | None:
    """The hair length (mm) of a recording's 'brush' section (its preset and its own geometry);
    None when it names no brush this extension has."""
    try:
        return Recording(np.zeros((1, 6)), brush=brush).resolve()[1].hair_length_mm
    except RecordingError:
        return None


def own_hair_length(brush: dict) -> bool:
    """Whether a recording's 'brush' section gives its own hair length (its samples then
    stay whatever brush preset is chosen)."""
    geometry = brush.get("geometry")
    return isinstance(geometry, dict) and "hair_length_mm" in geometry


def hair_shift(recorded_brush: dict, rec: Recording) -> float:
    """How far (mm) the samples of a recording made with ``recorded_brush`` move up for the
    brush ``rec`` is rendered with: the change of hair length, so every sample hovers above or
    presses into the touching height as far as it was recorded to (a sample's z is the brush
    base's height; the brush empty and its keyframes move as much, scene_setup.
    follow_hair_length). 0 when the hair length is the same (the recording's own
    'brush.geometry' keeps it) or the recorded brush is unknown."""
    before = hair_length_of(recorded_brush)
    return 0.0 if before is None else rec.resolve()[1].hair_length_mm - before


def store_recording(st, rec: Recording) -> bpy.types.Text:
    text = st.recording
    if text is None:
        text = bpy.data.texts.new(RECORDING_TEXT)
        st.recording = text
    text.from_string(recording_text(rec))
    # counted here, so the sidebar shows them without reading the text
    text[SAMPLES_TAG] = len(rec.samples)
    text[DIPS_TAG] = len(rec.dips)
    text[OWN_COLOR_TAG] = sum(not dp.follows_ink for dp in rec.dips_or_default())
    tag_work(text, rec)
    hair = None if own_hair_length(rec.brush) else hair_length_of(rec.brush)
    if hair is not None:  # the sidebar compares it with the brush chosen
        text[HAIR_TAG] = hair
    elif HAIR_TAG in text:
        del text[HAIR_TAG]
    if "scale" in rec.brush:  # the sidebar says the brush was made smaller or larger
        text[SCALE_TAG] = brush_scale(rec.brush)
    elif SCALE_TAG in text:
        del text[SCALE_TAG]
    return text


def tag_work(text, rec: Recording):
    """Keep on the text what the sidebar shows of a work (sim.writing.work): its cells'
    characters in writing order and whether it is signed; nothing for a recording without one."""
    work = rec.extra.get(WORK_KEY) if isinstance(rec.extra, dict) else None
    layout = work.get("layout") if isinstance(work, dict) else None
    cells = layout.get("cells") if isinstance(layout, dict) else None
    if not isinstance(cells, list):
        for tag in (WORK_TAG, SIGNED_TAG):
            if tag in text:
                del text[tag]
        return
    text[WORK_TAG] = "".join(str(c.get("char", "?"))[:1] for c in cells if isinstance(c, dict))
    signed = bool(layout.get("seal")) or any(
        isinstance(c, dict) and c.get("role") != "text" for c in cells
    )
    text[SIGNED_TAG] = int(signed)


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
        "seed": rec.seed % (checks.MAX_INT_PROPERTY + 1),
        "sample_rate_hz": rec.sample_rate_hz,
        "brush_preset": rec.preset_name("brush"),
        "paper_preset": rec.preset_name("paper"),
        "ink_preset": rec.preset_name("ink"),
    }
    q, _geom, _paper, _ink = rec.resolve()
    _check_fits(st, "paper_capacity", _paper.capacity)
    _check_fits(st, "paper_fibre", _paper.fibre)
    _check_fits(st, "paper_texture", _paper.texture)
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
    st.paper_texture = _paper.texture
    st.ink_color = _ink.color  # after the ink preset, which sets its own
    st.seed_of_recording = str(rec.seed) if rec.seed > checks.MAX_INT_PROPERTY else ""


def _check_fits(group, name: str, value):
    """UserError unless ``value`` fits the property (its range, or its enum's items)."""
    prop = group.bl_rna.properties[name]
    if prop.type == "ENUM":
        if value not in {item.identifier for item in prop.enum_items}:
            kind = prop.name.lower().removesuffix(" preset")
            raise checks.UserError(f"'{value}' is not a {kind} preset of this extension")
    elif not prop.hard_min <= value <= prop.hard_max:
        raise checks.UserError(
            f"{prop.name} {value} is outside what the setting holds "
            f"({prop.hard_min:g} to {prop.hard_max:g})"
        )


def new_recording(scene, samples, dips=None, written=None) -> Recording:
    """A validated recording of ``samples`` at the scene's sample rate and settings, timed from
    the scene's first frame (``written``: the recording the samples were written in, whose
    brush's size stays, ``with_brush_scale``); raises UserError (bad settings) or
    RecordingError (bad samples)."""
    st = checks.settings(scene)
    rec = Recording(np.asarray(samples, dtype=float), sample_rate_hz=float(st.sample_rate_hz))
    rec.dips = list(dips) if dips is not None else [current_dip(st, 0)]
    rec.extra["blender"] = {"frame_start": scene.frame_start}
    d = rec.to_dict()
    d.update(scene_overrides(st))
    return with_brush_scale(from_dict(d), written)


def with_brush_scale(rec: Recording, written: Recording | None) -> Recording:
    """``rec`` with the brush made as large as ``written``'s (its 'brush.scale': the writer's
    brush for the size of the writing, sim.writing.brush_size), or as it is (no ``written``,
    or one written with the brush at its preset's size)."""
    if written is None or "scale" not in written.brush:
        return rec
    return replace(rec, brush={**rec.brush, "scale": written.brush["scale"]})


def settings_recording(scene) -> Recording:
    """A one-sample recording that carries only the scene's settings (brush, paper, ink,
    quality, rate, seed): the template from which the engine writes or fits."""
    return new_recording(scene, [[0.0, 0.0, 100.0, 0.0, 0.0, 0.0]])


def current_dip(st, before_sample: int, color=None) -> Dip:
    """A dip of the sidebar's depth and wetness that loads the scene's Ink Colour, whatever
    it becomes later; or, given a ``color``, keeps that colour (a second ink)."""
    own = color is not None
    return Dip(
        before_sample,
        float(st.dip_depth),
        tuple(float(c) for c in (color if own else st.ink_color)),
        float(st.dip_wetness),
        follows_ink=not own,
    )


def following_ink(dips) -> list:
    """The dips, each loading the scene's Ink Colour (the writer's dips, made in the ink)."""
    return [replace(dp, follows_ink=True) for dp in dips]
