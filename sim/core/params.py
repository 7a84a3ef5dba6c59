# SPDX-License-Identifier: GPL-3.0-or-later
"""Quality parameters (Sec. 7.1, Eq. 1, Fig. 8(a)), brush/paper/ink specs and the preset library.

Presets are plain JSON files in ``presets/{brushes,papers,inks}/`` at the repository (and
add-on) root, loaded by plain Python so that they are testable without Blender.
"""

from __future__ import annotations

import copy
import math
import numbers
import sys
from dataclasses import asdict, dataclass, field, fields, replace
from pathlib import Path

from .jsonio import read_json

PRESET_DIR = Path(__file__).resolve().parents[2] / "presets"
PRESET_KINDS = {"brush": "brushes", "paper": "papers", "ink": "inks", "quality": "qualities"}

# Fig. 8(a): name, concise meaning, category, where used.
QUALITY_DOC = {
    "e": (
        "Elasticity of the hair: springiness. Higher recovers faster from bending (Eq. 14) "
        "and deforms more per unit pressure (Eq. 12, 13); (1 - e) is the hair's rigidity in "
        "the inner stress (Eq. 10).",
        1,
    ),
    "tre": (
        "Splitting threshold: the inner stress at which the brush branches into several "
        "hair clusters (Eq. 18). Lower splits more easily.",
        1,
    ),
    "nu": (
        "Relocation factor: how slowly the middle control ellipse moves toward the middle "
        "of the key points (Eq. 17). Paper's default 0.75.",
        1,
    ),
    "re": (
        "Rotation coefficient: how much moving along the ellipse's minor axis twists the "
        "brush (Eq. 16).",
        1,
    ),
    "ie": (
        "Elongation coefficient: how much moving across the ellipse's minor axis flattens "
        "and widens the brush (Eq. 16).",
        1,
    ),
    "sm": (
        "Paper grip (the paper calls it smoothness): scales the pressure the paper returns "
        "to a moving brush (Eq. 12).",
        1,
    ),
    "ren": (
        "Colour rendering control: how readily fast, pressed strokes skip pixels, leaving "
        "dry-brush 'flying white' (Eq. 27).",
        2,
    ),
    "eta": (
        "Ink diffusion distance between hair clusters: key points closer than this share "
        "ink (Eq. 20).",
        2,
    ),
    "ab": (
        "Paper absorbency: how fast the brush loses ink to the paper (Eq. 15) and how much "
        "a pixel keeps of its own wetness (Eq. 24, 27).",
        2,
    ),
    "pw": (
        "Diffusion control: the share of ink that flows between neighbouring hair clusters "
        "each step (Eq. 20).",
        2,
    ),
    "dry": ("Drying speed of the paper: wetness lost per second (Eq. 24).", 2),
}
QP1 = ("e", "tre", "nu", "re", "ie", "sm")  # shape of the strokes' boundaries
QP2 = ("ren", "eta", "ab", "pw", "dry")  # texture of the strokes
BRUSH_QUALITY = ("e", "tre", "nu", "re", "ie", "ren", "eta")
PAPER_QUALITY = ("sm", "ab", "pw", "dry")

HOVER_MM = 5.0  # how high the brush base hovers above touching height between strokes
# The paper's per-time-slice updates (Sec. 5.2.2, Eq. 15, 16, 26) are applied at this reference
# rate and scaled by dt * REF_RATE otherwise, so a gesture leaves the same artwork at any rate.
REF_RATE = 30.0  # time slices per second
MAX_PAPER_SIDE_PX = 8192
MAX_PAPER_PIXELS = 8192 * 8192
PAPER_CAPACITY_RANGE = (1e-3, 1e6)  # a preset's wetness capacity
INK_PIGMENT_RANGE = (0.05, 1.0)  # an ink's pigment per unit of liquid (1: full strength)
PAPER_TEXTURE_MAX = 0.3  # the strongest paper texture (sim.paper.texture; 0.05: xuan's own)
INK_FACTOR_RANGE = (-1.0, 1.0)  # an ink preset's per-mm factors of Eq. 5
# a brush made smaller or larger in proportion (a recording's 'brush.scale'; the writer's
# brush for the size of the writing, sim.writing.brush_size): 1/4 to 4 times the preset's
BRUSH_SCALE_RANGE = (0.25, 4.0)


class ParameterError(ValueError):
    """A parameter or preset is missing or out of range; the message names the field."""


def is_number(value) -> bool:
    """A real number, not a bool (True is an int in Python) and not a string."""
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def number_within(value, lo=-math.inf, hi=math.inf) -> bool:
    """A finite number in [lo, hi] (whole numbers are compared exactly, and must fit a float)."""
    if not is_number(value):
        return False
    if isinstance(value, numbers.Integral):
        v = int(value)
        return -sys.float_info.max <= v <= sys.float_info.max and lo <= v <= hi
    v = float(value)
    return math.isfinite(v) and lo <= v <= hi


def short_repr(value) -> str:
    """A value for a message: huge integers by their size, long reprs cut."""
    if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 80:
        return f"an integer of {value.bit_length()} bits"
    r = repr(value)
    return r if len(r) <= 60 else r[:57] + "..."


def _check_unit(name: str, value) -> float:
    if not is_number(value):
        raise ParameterError(
            f"quality parameter '{name}' must be a number, got {short_repr(value)}"
        )
    if not number_within(value, 0.0, 1.0):
        raise ParameterError(
            f"quality parameter '{name}' must lie in [0, 1], got {short_repr(value)}"
        )
    return float(value)


@dataclass(frozen=True)
class QualityParams:
    """Qp = (Qp1, Qp2), Eq. 1. Every value lies in [0, 1]."""

    e: float = 0.5
    tre: float = 0.45
    nu: float = 0.75
    re: float = 0.45
    ie: float = 0.45
    sm: float = 0.5
    ren: float = 0.5
    eta: float = 0.45
    ab: float = 0.5
    pw: float = 0.35
    dry: float = 0.25

    def __post_init__(self):
        for f in fields(self):
            object.__setattr__(self, f.name, _check_unit(f.name, getattr(self, f.name)))

    @classmethod
    def names(cls) -> tuple[str, ...]:
        return tuple(f.name for f in fields(cls))

    def to_dict(self) -> dict:
        return asdict(self)

    def with_values(self, values: dict) -> QualityParams:
        unknown = set(values) - set(self.names())
        if unknown:
            raise ParameterError(
                f"unknown quality parameter(s) {sorted(unknown)}; known: {list(self.names())}"
            )
        return replace(self, **{k: _check_unit(k, v) for k, v in values.items()})

    def vector(self, names=QP1 + QP2) -> list[float]:
        return [getattr(self, n) for n in names]


@dataclass(frozen=True)
class BrushGeometry:
    """The free (initial) state of a brush, Sec. 3.4: hair length, the bottom control circle's
    radius r (Eq. 2), the middle control ellipse's diameter (a = b) and location loc (Eq. 6)."""

    hair_length_mm: float = 30.0
    base_radius_mm: float = 3.9
    belly_diameter_mm: float = 8.8
    belly_loc: float = 0.32
    key_points: int = 9

    def __post_init__(self):
        checks = {
            "hair_length_mm": (1.0, 200.0),
            "base_radius_mm": (0.2, 50.0),
            "belly_diameter_mm": (0.2, 100.0),
            "belly_loc": (0.05, 0.9),
        }
        for name, (lo, hi) in checks.items():
            v = getattr(self, name)
            if not number_within(v, lo, hi):
                raise ParameterError(
                    f"brush geometry '{name}' must lie in [{lo}, {hi}], got {short_repr(v)}"
                )
        k = self.key_points
        if isinstance(k, bool) or not isinstance(k, int) or not 5 <= k <= 32:
            raise ParameterError(
                f"brush geometry 'key_points' must be an integer in [5, 32], got {short_repr(k)}"
            )

    def scaled(self, k: float) -> BrushGeometry:
        """The same brush made ``k`` times as large (a smaller brush for smaller writing): its
        hair length, base radius and belly diameter times k; where the belly sits, a share of
        the hair, and the key points are the same."""
        return replace(
            self,
            hair_length_mm=self.hair_length_mm * k,
            base_radius_mm=self.base_radius_mm * k,
            belly_diameter_mm=self.belly_diameter_mm * k,
        )


@dataclass(frozen=True)
class PaperSpec:
    """Paper colour (RGB, 0..1) and wetness capacity: the upper bound of the paper's wetness
    (Sec. 6, before Eq. 25). Wetness above it saturates and spreads to the neighbours."""

    color: tuple = (1.0, 1.0, 1.0)
    capacity: float = 1.0
    fibre: float = 0.0  # how much the grain shows in thin ink, 0..1 (model addition, paper_grain)
    texture: float = 0.0  # how much the sheet's clouds and fibres show, 0..PAPER_TEXTURE_MAX
    # (model addition, sim.paper.texture; 0: the flat colour)


@dataclass(frozen=True)
class InkSpec:
    color: tuple = (0.03, 0.03, 0.04)
    wetness: float = 0.9
    depth: float = 0.7
    wr: float = -0.02  # radiation-mode wetness factor per mm (Eq. 5)
    cr: float = -0.01  # radiation-mode colour factor per mm (Eq. 5)
    wv: tuple = (0.0, 0.0, 0.0)  # vector-mode wetness vector per mm, brush frame (Eq. 5)
    cv: tuple = (0.0, 0.0, 0.0)  # vector-mode colour vector per mm, brush frame (Eq. 5)
    pigment: float = 1.0  # pigment per unit of liquid against a full-strength ink (see FULL_WET)


@dataclass(frozen=True)
class Preset:
    kind: str
    name: str
    label: str
    description: str
    data: dict = field(repr=False)


def preset_names(kind: str, directory: Path | None = None) -> list[str]:
    d = (directory or PRESET_DIR) / PRESET_KINDS[kind]
    return sorted(p.stem for p in d.glob("*.json"))


_BAD_NAME_CHARS = ("/", "\\", "\x00")


_PRESET_CACHE: dict = {}  # path -> ((mtime, size), data): a preset file is read once


def _read_preset(path: Path, kind: str):
    """A preset file's JSON values, read again only when the file changed (a copy each call,
    so no caller changes what the next one gets)."""
    st = path.stat()
    stamp = (st.st_mtime_ns, st.st_size)
    hit = _PRESET_CACHE.get(path)
    if hit is None or hit[0] != stamp:
        data = read_json(path, f"{kind} preset file", ParameterError, max_bytes=2**20)
        hit = _PRESET_CACHE[path] = (stamp, data)
    return copy.deepcopy(hit[1])


def load_preset(kind: str, name: str, directory: Path | None = None) -> Preset:
    if kind not in PRESET_KINDS:
        raise ParameterError(f"unknown preset kind {kind!r}; known: {sorted(PRESET_KINDS)}")
    ok_name = isinstance(name, str) and name and not any(c in name for c in _BAD_NAME_CHARS)
    path = (directory or PRESET_DIR) / PRESET_KINDS[kind] / f"{name}.json"
    if not ok_name or not path.is_file():
        raise ParameterError(
            f"unknown {kind} preset {short_repr(name)}; available: {preset_names(kind, directory)}"
        )
    data = _read_preset(path, kind)
    if not isinstance(data, dict) or data.get("kind") != kind:
        raise ParameterError(f"{path.name}: must be a JSON object whose 'kind' is {kind!r}")
    for key, typ in (("label", str), ("description", str), ("quality", dict)):
        if key in data and not isinstance(data[key], typ):
            raise ParameterError(f"{kind} preset {path.name}: '{key}' has the wrong type")
    return Preset(kind, name, data.get("label", name), data.get("description", ""), data)


def quality_from_presets(brush: Preset | None, paper: Preset | None) -> dict:
    values = {}
    for preset, allowed in ((brush, BRUSH_QUALITY), (paper, PAPER_QUALITY)):
        if preset is None:
            continue
        q = preset.data.get("quality", {})
        for k, v in q.items():
            if k not in allowed:
                raise ParameterError(
                    f"{preset.kind} preset {preset.name!r}: quality '{k}' does not belong to a "
                    f"{preset.kind} (allowed: {list(allowed)})"
                )
            values[k] = v
    return values


def _section(preset: Preset, key: str) -> dict:
    v = preset.data.get(key, {})
    if not isinstance(v, dict):
        raise ParameterError(f"{preset.kind} preset {preset.name!r}: '{key}' must be an object")
    return v


def _preset_num(preset: Preset, d: dict, key: str, default, lo: float, hi: float) -> float:
    """A number of a preset, checked: finite and within [lo, hi]."""
    v = d.get(key, default)
    if not number_within(v, lo, hi):
        raise ParameterError(
            f"{preset.kind} preset {preset.name!r}: '{key}' must be a number in [{lo}, {hi}], "
            f"got {short_repr(v)}"
        )
    return float(v)


def _preset_vec(preset: Preset, d: dict, key: str, default, lo: float, hi: float) -> tuple:
    """Three numbers of a preset (a colour or a vector), each within [lo, hi]."""
    v = d.get(key, default)
    if not isinstance(v, (list, tuple)) or len(v) != 3:
        raise ParameterError(
            f"{preset.kind} preset {preset.name!r}: '{key}' must be a list of 3 numbers"
        )
    return tuple(_preset_num(preset, {key: c}, key, 0.0, lo, hi) for c in v)


def geometry_from_preset(preset: Preset | None) -> BrushGeometry:
    if preset is None:
        return BrushGeometry()
    g = _section(preset, "geometry")
    known = {f.name for f in fields(BrushGeometry)}
    if set(g) - known:
        raise ParameterError(
            f"brush preset {preset.name!r}: unknown geometry field(s) {sorted(set(g) - known)}"
        )
    try:
        return BrushGeometry(**g)
    except ParameterError as exc:
        raise ParameterError(f"brush preset {preset.name!r}: {exc}") from None


def paper_from_preset(preset: Preset | None) -> PaperSpec:
    if preset is None:
        return PaperSpec()
    d = preset.data
    return PaperSpec(
        color=_preset_vec(preset, d, "color", PaperSpec.color, 0.0, 1.0),
        capacity=_preset_num(preset, d, "capacity", PaperSpec.capacity, *PAPER_CAPACITY_RANGE),
        fibre=_preset_num(preset, d, "fibre", PaperSpec.fibre, 0.0, 1.0),
        texture=_preset_num(preset, d, "texture", PaperSpec.texture, 0.0, PAPER_TEXTURE_MAX),
    )


def ink_from_preset(preset: Preset | None) -> InkSpec:
    if preset is None:
        return InkSpec()
    d = preset.data
    rad, vec = _section(preset, "radiation"), _section(preset, "vector")
    lo, hi = INK_FACTOR_RANGE
    return InkSpec(
        color=_preset_vec(preset, d, "color", InkSpec.color, 0.0, 1.0),
        wetness=_preset_num(preset, d, "wetness", InkSpec.wetness, 0.0, 1.0),
        depth=_preset_num(preset, d, "depth", InkSpec.depth, 0.0, 1.0),
        wr=_preset_num(preset, rad, "wr", InkSpec.wr, lo, hi),
        cr=_preset_num(preset, rad, "cr", InkSpec.cr, lo, hi),
        wv=_preset_vec(preset, vec, "wv", InkSpec.wv, lo, hi),
        cv=_preset_vec(preset, vec, "cv", InkSpec.cv, lo, hi),
        pigment=_preset_num(preset, d, "pigment", InkSpec.pigment, *INK_PIGMENT_RANGE),
    )
