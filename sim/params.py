# SPDX-License-Identifier: GPL-3.0-or-later
"""Quality parameters (Sec. 7.1, Eq. 1, Fig. 8(a)), brush/paper/ink specs and the preset library.

Presets are plain JSON files in ``presets/{brushes,papers,inks}/`` at the repository (and
add-on) root, loaded by plain Python so that they are testable without Blender.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, field, fields, replace
from pathlib import Path

PRESET_DIR = Path(__file__).resolve().parent.parent / "presets"
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

MAX_PAPER_SIDE_PX = 8192
MAX_PAPER_PIXELS = 8192 * 8192


class ParameterError(ValueError):
    """A parameter or preset is missing or out of range; the message names the field."""


def _check_unit(name: str, value) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(
            f"quality parameter '{name}' must be a number, got {value!r}"
        ) from None
    if not math.isfinite(v) or v < 0.0 or v > 1.0:
        raise ParameterError(f"quality parameter '{name}' must lie in [0, 1], got {value!r}")
    return v


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
            if not isinstance(v, (int, float)) or not math.isfinite(v) or not lo <= v <= hi:
                raise ParameterError(f"brush geometry '{name}' must lie in [{lo}, {hi}], got {v!r}")
        if not isinstance(self.key_points, int) or not 5 <= self.key_points <= 32:
            raise ParameterError(
                f"brush geometry 'key_points' must be an integer in [5, 32], "
                f"got {self.key_points!r}"
            )


@dataclass(frozen=True)
class PaperSpec:
    """Paper colour (RGB, 0..1) and wetness capacity: the upper bound of the paper's wetness
    (Sec. 6, before Eq. 25). Wetness above it saturates and spreads to the neighbours."""

    color: tuple = (1.0, 1.0, 1.0)
    capacity: float = 1.0


@dataclass(frozen=True)
class InkSpec:
    color: tuple = (0.03, 0.03, 0.04)
    wetness: float = 0.9
    depth: float = 0.7
    wr: float = -0.02  # radiation-mode wetness factor per mm (Eq. 5)
    cr: float = -0.01  # radiation-mode colour factor per mm (Eq. 5)
    wv: tuple = (0.0, 0.0, 0.0)  # vector-mode wetness vector per mm, brush frame (Eq. 5)
    cv: tuple = (0.0, 0.0, 0.0)  # vector-mode colour vector per mm, brush frame (Eq. 5)


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


def load_preset(kind: str, name: str, directory: Path | None = None) -> Preset:
    if kind not in PRESET_KINDS:
        raise ParameterError(f"unknown preset kind {kind!r}; known: {sorted(PRESET_KINDS)}")
    path = (directory or PRESET_DIR) / PRESET_KINDS[kind] / f"{name}.json"
    if not isinstance(name, str) or "/" in name or "\\" in name or not path.is_file():
        raise ParameterError(
            f"unknown {kind} preset {name!r}; available: {preset_names(kind, directory)}"
        )
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except json.JSONDecodeError as exc:
        raise ParameterError(f"{kind} preset file {path.name} is not valid JSON: {exc}") from None
    if data.get("kind") != kind:
        raise ParameterError(f"{path.name}: 'kind' must be {kind!r}")
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


def geometry_from_preset(preset: Preset | None) -> BrushGeometry:
    if preset is None:
        return BrushGeometry()
    g = dict(preset.data.get("geometry", {}))
    try:
        return BrushGeometry(**g)
    except TypeError as exc:
        raise ParameterError(f"brush preset {preset.name!r}: bad geometry: {exc}") from None


def paper_from_preset(preset: Preset | None) -> PaperSpec:
    if preset is None:
        return PaperSpec()
    d = preset.data
    return PaperSpec(
        color=tuple(float(c) for c in d.get("color", (1, 1, 1))),
        capacity=float(d.get("capacity", 1.0)),
    )


def ink_from_preset(preset: Preset | None) -> InkSpec:
    if preset is None:
        return InkSpec()
    d = preset.data
    rad = d.get("radiation", {})
    vec = d.get("vector", {})
    return InkSpec(
        color=tuple(float(c) for c in d.get("color", InkSpec.color)),
        wetness=float(d.get("wetness", InkSpec.wetness)),
        depth=float(d.get("depth", InkSpec.depth)),
        wr=float(rad.get("wr", InkSpec.wr)),
        cr=float(rad.get("cr", InkSpec.cr)),
        wv=tuple(float(c) for c in vec.get("wv", InkSpec.wv)),
        cv=tuple(float(c) for c in vec.get("cv", InkSpec.cv)),
    )
