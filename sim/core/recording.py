# SPDX-License-Identifier: GPL-3.0-or-later
"""Recordings (Sec. 1.2, 10): a small versioned JSON file of the brush's 6-DOF samples, the dips
and the settings, from which the artwork is rebuilt exactly.

Loading validates everything and raises ``RecordingError`` naming the offending field; nothing
malformed reaches the engine.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields, replace
from pathlib import Path

import numpy as np

from .files import write_json_atomic
from .jsonio import decode_text, parse_json, read_json
from .params import (
    BRUSH_SCALE_RANGE,
    MAX_PAPER_PIXELS,
    MAX_PAPER_SIDE_PX,
    PAPER_CAPACITY_RANGE,
    PAPER_TEXTURE_MAX,
    BrushGeometry,
    InkSpec,
    ParameterError,
    QualityParams,
    geometry_from_preset,
    ink_from_preset,
    is_number,
    load_preset,
    number_within,
    paper_from_preset,
    quality_from_presets,
    short_repr,
)

FORMAT = "hairy-brush-recording"
VERSION = 1
DEFAULT_BRUSH = "wolf_kaishu"  # the brush that writes best (issue 16: the defaults write best)
DEFAULT_PAPER = "sized_xuan"
DEFAULT_INK = "sumi_black"
MAX_SAMPLES = 2_000_000
PAPER_MM_RANGE = (1.0, 5000.0)  # a side of the paper
PX_PER_MM_RANGE = (0.1, 200.0)
MAX_DIPS = 10_000  # a dip before every stroke of a long artwork, with room to spare
MAX_SEED = 2**64 - 1  # PCG64 takes any non-negative integer; a recording keeps 64 bits
MAX_RESTART = 2**32 - 1  # a restarting dip's stream number (Dip.restart)
Z_LIMIT_MM = 1000.0
ANGLE_LIMIT_DEG = 89.0
# the rotation about the handle may wind on (a twisting stroke baked from keyframes); a bound
# keeps its radians exact enough for cos/sin (issue 30: r = 1e308 became inf, then NaN ink)
ROTATION_LIMIT_DEG = 1_000_000.0  # about 2,800 turns


SAMPLE_DECIMALS = 5


def quantise(samples, decimals: int = SAMPLE_DECIMALS) -> np.ndarray:
    """Samples (or a surface's frames) exactly as a saved recording holds them: each value
    rounded to ``decimals`` by Python's correctly rounded ``round``, so that whatever simulated
    them live or while writing replays bit for bit from the file."""
    a = np.asarray(samples, dtype=float)
    return np.array([round(float(v), decimals) for v in a.ravel()]).reshape(a.shape)


class RecordingError(ValueError):
    """A recording is malformed; the message names the field."""


@dataclass
class Dip:
    """A dip before a sample; a field a recording leaves out is the paper's default dip's: "a
    full dip in black ink" (depth 1, black), as wet as the default ink loads.

    ``follows_ink`` (added beyond the paper): the dip loads the recording's ink colour (its
    'ink' section's colour, else its ink preset's), so a new ink colour recolours the work;
    ``color`` is then only the colour it had when recorded (what an engine that does not know
    the field loads). False, as for every dip of a recording that leaves the field out: the dip
    keeps its own colour (a second ink)."""

    before_sample: int
    depth: float = 1.0
    color: tuple = (0.0, 0.0, 0.0)
    wetness: float = InkSpec.wetness
    follows_ink: bool = False
    # a dip that starts a cell of a composed work (sim.writing.work): the brush is made new and
    # its random draws come from the stream (seed, restart) from then on, so that the cell's
    # writing depends on nothing before it (Simulation._restart); None: an ordinary dip
    restart: int | None = None

    def color_with(self, ink: InkSpec) -> tuple:
        """The colour this dip loads with the recording's resolved ``ink``."""
        return tuple(ink.color) if self.follows_ink else tuple(self.color)

    def to_dict(self):
        d = {
            "before_sample": self.before_sample,
            "depth": self.depth,
            "color": list(self.color),
            "wetness": self.wetness,
        }
        if self.follows_ink:  # left out otherwise: older recordings' text stays as it was
            d["follows_ink"] = True
        if self.restart is not None:
            d["restart"] = self.restart
        return d


@dataclass
class Recording:
    samples: np.ndarray  # (N, 6): x, y, z mm; d, q, r degrees
    width_mm: float = 200.0
    height_mm: float = 200.0
    px_per_mm: float = 5.0
    sample_rate_hz: float = 120.0
    seed: int = 0
    brush: dict = field(default_factory=lambda: {"preset": DEFAULT_BRUSH})
    paper_preset: str = DEFAULT_PAPER
    ink: dict = field(default_factory=lambda: {"preset": DEFAULT_INK})
    quality: dict = field(default_factory=dict)
    dips: list = field(default_factory=list)
    extra: dict = field(default_factory=dict)  # fields we keep but do not interpret
    # the paper preset's colour (RGB, 0..1) and capacity (Sec. 6, Eq. 25), overridden; {} keeps
    # the preset's
    paper_overrides: dict = field(default_factory=dict)

    # ---------------------------------------------------------------- derived settings
    @property
    def width_px(self) -> int:
        return max(1, int(round(self.width_mm * self.px_per_mm)))

    @property
    def height_px(self) -> int:
        return max(1, int(round(self.height_mm * self.px_per_mm)))

    def preset_name(self, kind: str) -> str:
        """The name of the recording's brush, paper or ink preset (one way for all three)."""
        if kind == "paper":
            return self.paper_preset
        section, default = (
            (self.brush, DEFAULT_BRUSH) if kind == "brush" else (self.ink, DEFAULT_INK)
        )
        return section.get("preset", default)

    def resolve(self):
        """(QualityParams, BrushGeometry, PaperSpec, InkSpec) from presets plus overrides."""
        try:
            bp, pp, ip = (load_preset(k, self.preset_name(k)) for k in ("brush", "paper", "ink"))
            values = quality_from_presets(bp, pp)
            values.update(self.quality)
            q = QualityParams().with_values(values)
            geom = geometry_from_preset(bp)
            if "scale" in self.brush:  # the brush made smaller or larger (brush_scale)
                geom = geom.scaled(brush_scale(self.brush))
            geom = _geometry_override(geom, self.brush.get("geometry"))
            paper = replace(paper_from_preset(pp), **self.paper_overrides)
            ink = ink_from_preset(ip)
            if "color" in self.ink:  # the recording's own ink colour (see Dip.follows_ink)
                ink = replace(ink, color=tuple(float(c) for c in self.ink["color"]))
            return q, geom, paper, ink
        except ParameterError as exc:
            raise RecordingError(str(exc)) from None

    def dips_or_default(self) -> list:
        if self.dips:
            return self.dips
        return [Dip(0)]  # the default dip (see Dip): black, whatever the ink colour

    def to_dict(self) -> dict:
        d = {
            "format": FORMAT,
            "version": VERSION,
            "paper": {
                "width_mm": self.width_mm,
                "height_mm": self.height_mm,
                "px_per_mm": self.px_per_mm,
                "preset": self.paper_preset,
                **{k: list(v) if k == "color" else v for k, v in self.paper_overrides.items()},
            },
            "brush": dict(self.brush),
            "ink": dict(self.ink),
            "quality": dict(self.quality),
            "sample_rate_hz": self.sample_rate_hz,
            "seed": self.seed,
            "samples": quantise(self.samples).tolist(),
            "dips": [dp.to_dict() for dp in self.dips],
        }
        d.update(self.extra)
        return d

    def save(self, path) -> None:
        """Write the recording as compact JSON, whole or not at all (a failure keeps the old
        file; see ``files.write_atomic``)."""
        write_json_atomic(path, self.to_dict())


# ------------------------------------------------------------------------- validation
def brush_scale(brush: dict) -> float:
    """A recording's 'brush.scale' (1 without one): how many times as large as its preset the
    brush is, its hair, base and belly (``BrushGeometry.scaled``; the writer takes a smaller
    brush for smaller writing, ``sim.writing.brush_size``); its 'geometry' values, if any, are
    set after it."""
    if "scale" not in brush:
        return 1.0
    return _num(brush["scale"], "'brush.scale'", *BRUSH_SCALE_RANGE)


def _geometry_override(geom: BrushGeometry, override) -> BrushGeometry:
    """The preset's brush geometry with the recording's 'brush.geometry' values."""
    if override is None:
        return geom
    if not isinstance(override, dict):
        raise RecordingError("'brush.geometry' must be an object")
    known = [f.name for f in fields(BrushGeometry)]
    unknown = sorted(str(k) for k in override if k not in known)
    if unknown:
        raise RecordingError(f"unknown field(s) {unknown} in 'brush.geometry' (known: {known})")
    try:
        return replace(geom, **override)
    except ParameterError as exc:
        raise RecordingError(f"'brush.geometry': {exc}") from None


def _num(value, where: str, lo=-math.inf, hi=math.inf, integer=False):
    if not is_number(value):
        raise RecordingError(
            f"{where} must be a number, got {type(value).__name__} {short_repr(value)}"
        )
    if not number_within(value):  # NaN, infinities, whole numbers beyond any float
        raise RecordingError(f"{where} must be finite, got {short_repr(value)}")
    if not isinstance(value, int):
        value = float(value)
        if integer and not value.is_integer():
            raise RecordingError(f"{where} must be a whole number, got {value!r}")
    if not lo <= value <= hi:
        raise RecordingError(f"{where} must lie in [{lo}, {hi}], got {short_repr(value)}")
    return int(value) if integer else float(value)


def _obj(d, key, where, required=True):
    if key not in d:
        if required:
            raise RecordingError(f"missing field '{where}'")
        return None
    v = d[key]
    if not isinstance(v, dict):
        raise RecordingError(f"'{where}' must be an object")
    return v


KNOWN_KEYS = {
    "format",
    "version",
    "paper",
    "brush",
    "ink",
    "quality",
    "sample_rate_hz",
    "seed",
    "samples",
    "dips",
}


def from_dict(d) -> Recording:
    """A checked Recording from a recording's JSON values; RecordingError names what is wrong."""
    if not isinstance(d, dict):
        raise RecordingError("a recording must be a JSON object")
    _check_format(d)
    width, height, ppm, paper_preset, paper_overrides = _paper(d)
    brush, ink, quality = _presets_and_quality(d)
    if "sample_rate_hz" not in d:
        raise RecordingError("missing field 'sample_rate_hz'")
    rate = _num(d["sample_rate_hz"], "'sample_rate_hz'", 1.0, 10000.0)
    seed = _num(d.get("seed", 0), "'seed'", 0, MAX_SEED, integer=True)
    arr = _samples(d, max(width, height))
    rec = Recording(
        samples=arr,
        width_mm=width,
        height_mm=height,
        px_per_mm=ppm,
        sample_rate_hz=rate,
        seed=seed,
        brush=brush,
        paper_preset=paper_preset,
        ink=ink,
        quality=quality,
        dips=_dips(d, len(arr)),
        extra={k: v for k, v in d.items() if k not in KNOWN_KEYS},
        paper_overrides=paper_overrides,
    )
    rec.resolve()  # presets exist and values are in range
    return rec


def _check_format(d: dict):
    if d.get("format") != FORMAT:
        raise RecordingError(f"field 'format' must be {FORMAT!r}, got {d.get('format')!r}")
    if "version" not in d:
        raise RecordingError("missing field 'version'")
    version = _num(d["version"], "'version'", integer=True)
    if version != VERSION:
        raise RecordingError(
            f"field 'version' {version} is not supported (this engine reads {VERSION})"
        )


def _paper(d: dict):
    """(width mm, height mm, px per mm, preset, overrides) of the 'paper' section."""
    paper = _obj(d, "paper", "paper")
    for k in ("width_mm", "height_mm", "px_per_mm"):
        if k not in paper:
            raise RecordingError(f"missing field 'paper.{k}'")
    width = _num(paper["width_mm"], "'paper.width_mm'", *PAPER_MM_RANGE)
    height = _num(paper["height_mm"], "'paper.height_mm'", *PAPER_MM_RANGE)
    ppm = _num(paper["px_per_mm"], "'paper.px_per_mm'", *PX_PER_MM_RANGE)
    wpx, hpx = round(width * ppm), round(height * ppm)
    if wpx > MAX_PAPER_SIDE_PX or hpx > MAX_PAPER_SIDE_PX or wpx * hpx > MAX_PAPER_PIXELS:
        raise RecordingError(
            f"paper of {wpx} x {hpx} px is too large: at most {MAX_PAPER_SIDE_PX} px a side "
            f"(reduce 'paper.px_per_mm' or the paper's size)"
        )
    preset = paper.get("preset", DEFAULT_PAPER)
    if not isinstance(preset, str):
        raise RecordingError("'paper.preset' must be a preset name")
    return width, height, ppm, preset, _paper_overrides(paper)


def _presets_and_quality(d: dict):
    """The 'brush' and 'ink' sections and the 'quality' values, checked."""
    brush = _obj(d, "brush", "brush", required=False) or {"preset": DEFAULT_BRUSH}
    ink = _obj(d, "ink", "ink", required=False) or {"preset": DEFAULT_INK}
    for name, sec in (("brush", brush), ("ink", ink)):
        if "preset" in sec and not isinstance(sec["preset"], str):
            raise RecordingError(f"'{name}.preset' must be a preset name")
    brush_scale(brush)
    if "color" in ink:
        ink = {**ink, "color": list(_color(ink["color"], "ink.color"))}
    quality = _obj(d, "quality", "quality", required=False) or {}
    known = QualityParams.names()
    for k, v in quality.items():
        if k not in known:
            raise RecordingError(f"unknown quality parameter 'quality.{k}' (known: {list(known)})")
        _num(v, f"'quality.{k}'", 0.0, 1.0)
    return brush, ink, quality


def _samples(d: dict, paper_side_mm: float) -> np.ndarray:
    """The 'samples' as an (N, 6) array, every value checked."""
    if "samples" not in d:
        raise RecordingError("missing field 'samples'")
    samples = d["samples"]
    if not isinstance(samples, list) or not samples:
        raise RecordingError("'samples' must be a non-empty list of [x, y, z, d, q, r]")
    if len(samples) > MAX_SAMPLES:
        raise RecordingError(f"'samples' has {len(samples)} entries; at most {MAX_SAMPLES}")
    for i, s in enumerate(samples):
        if not isinstance(s, list) or len(s) != 6:
            raise RecordingError(f"'samples[{i}]' must be a list of 6 numbers [x, y, z, d, q, r]")
        for k, v in enumerate(s):
            if not (math.isfinite(v) if type(v) is float else number_within(v)):
                raise RecordingError(
                    f"'samples[{i}][{k}]' must be a finite number, got {short_repr(v)}"
                )
    arr = np.asarray(samples, dtype=float)
    far = np.any(np.abs(arr[:, :2]) > 10 * paper_side_mm, axis=1)
    if far.any():
        raise RecordingError(f"'samples[{int(np.argmax(far))}]': x, y are far outside the paper")
    if np.any(np.abs(arr[:, 2]) > Z_LIMIT_MM):
        i = int(np.argmax(np.abs(arr[:, 2]) > Z_LIMIT_MM))
        raise RecordingError(f"'samples[{i}][2]' (z) must lie within +-{Z_LIMIT_MM} mm")
    if np.any(np.abs(arr[:, 3:5]) > ANGLE_LIMIT_DEG):
        i = int(np.argmax(np.any(np.abs(arr[:, 3:5]) > ANGLE_LIMIT_DEG, axis=1)))
        raise RecordingError(
            f"'samples[{i}]': deflections d, q must lie within +-{ANGLE_LIMIT_DEG} deg"
        )
    if np.any(np.abs(arr[:, 5]) > ROTATION_LIMIT_DEG):
        i = int(np.argmax(np.abs(arr[:, 5]) > ROTATION_LIMIT_DEG))
        raise RecordingError(
            f"'samples[{i}][5]' (rotation r) must lie within +-{ROTATION_LIMIT_DEG:,.0f} deg"
        )
    return arr


def _dips(d: dict, n_samples: int) -> list:
    """The 'dips', checked, in sample order."""
    dips_raw = d.get("dips", [])
    if not isinstance(dips_raw, list):
        raise RecordingError("'dips' must be a list")
    if len(dips_raw) > MAX_DIPS:
        raise RecordingError(f"'dips' has {len(dips_raw)} entries; at most {MAX_DIPS}")
    dips = []
    for i, dp in enumerate(dips_raw):
        where = f"dips[{i}]"
        if not isinstance(dp, dict):
            raise RecordingError(f"'{where}' must be an object")
        if "before_sample" not in dp:
            raise RecordingError(f"missing field '{where}.before_sample'")
        bs = _num(dp["before_sample"], f"'{where}.before_sample'", 0, n_samples, integer=True)
        depth = _num(dp.get("depth", Dip.depth), f"'{where}.depth'", 0.0, 1.0)
        wet = _num(dp.get("wetness", Dip.wetness), f"'{where}.wetness'", 0.0, 1.0)
        col = _color(dp.get("color", list(Dip.color)), f"{where}.color")
        follows = dp.get("follows_ink", False)
        if not isinstance(follows, bool):
            raise RecordingError(f"'{where}.follows_ink' must be true or false")
        restart = dp.get("restart")
        if restart is not None:
            restart = _num(restart, f"'{where}.restart'", 0, MAX_RESTART, integer=True)
        dips.append(Dip(bs, depth, col, wet, follows, restart))
    dips.sort(key=lambda x: x.before_sample)
    return dips


def _color(col, where: str) -> tuple:
    """An [r, g, b] colour of a recording, each in [0, 1]."""
    if not isinstance(col, list) or len(col) != 3:
        raise RecordingError(f"'{where}' must be [r, g, b]")
    return tuple(_num(c, f"'{where}[{k}]'", 0.0, 1.0) for k, c in enumerate(col))


def _paper_overrides(paper: dict) -> dict:
    """The 'paper' section's own colour, capacity, fibre and texture, checked."""
    out = {}
    if "color" in paper:
        out["color"] = _color(paper["color"], "paper.color")
    if "capacity" in paper:
        out["capacity"] = _num(paper["capacity"], "'paper.capacity'", *PAPER_CAPACITY_RANGE)
    if "fibre" in paper:
        out["fibre"] = _num(paper["fibre"], "'paper.fibre'", 0.0, 1.0)
    if "texture" in paper:
        out["texture"] = _num(paper["texture"], "'paper.texture'", 0.0, PAPER_TEXTURE_MAX)
    return out


def loads(text) -> Recording:
    """A recording from its JSON text (str, or bytes of UTF-8)."""
    if isinstance(text, (bytes, bytearray)):
        text = decode_text(bytes(text), "the recording", RecordingError)
    return from_dict(parse_json(text, "the recording", RecordingError))


def load(path) -> Recording:
    p = Path(path)
    if not p.is_file():
        raise RecordingError(f"no recording file at {p}")
    d = read_json(p, "recording", RecordingError)
    try:
        return from_dict(d)
    except RecordingError as exc:
        raise RecordingError(f"recording {p}: {exc}") from None
