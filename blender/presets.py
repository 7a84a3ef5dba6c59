# SPDX-License-Identifier: GPL-3.0-or-later
"""The presets as the sidebar shows them (labels, what choosing one sets) and copying a chosen
preset's values into the settings; the quality values' plain names and the groups they act on."""

from __future__ import annotations

from ..sim.core.params import (
    geometry_from_preset,
    ink_from_preset,
    load_preset,
    paper_from_preset,
    preset_names,
    quality_from_presets,
)

# what each quality value acts on, its plain name and what it does (the paper's symbol follows)
QUALITY_GROUPS = (
    ("Brush", "OUTLINER_OB_EMPTY", ("e", "tre", "nu", "re", "ie")),
    ("Ink in the Brush", "MOD_FLUIDSIM", ("ren", "eta", "pw")),
    ("Paper", "TEXTURE", ("sm", "ab", "dry")),
)
QUALITY_UI = {
    "e": (
        "Springiness",
        "Higher: bent hair springs back faster and bends further under the same "
        "pressure; lower: a stiff brush that keeps its shape",
    ),
    "tre": (
        "Split Threshold",
        "Lower: the hair splits into separate clusters under less "
        "pressure (cursive strokes with several tips)",
    ),
    "nu": (
        "Belly Lag",
        "Higher: the brush's belly follows the bent hair more slowly, so the "
        "stroke's body keeps its shape longer",
    ),
    "re": ("Twist", "Higher: moving sideways twists the brush's tip more around the handle"),
    "ie": ("Flattening", "Higher: moving sideways flattens and widens the brush more"),
    "ren": (
        "Flying White",
        "Higher: fast, pressed strokes skip more pixels and leave dry-brush streaks",
    ),
    "eta": (
        "Ink Sharing Distance",
        "Higher: hair clusters further apart still share ink inside the brush",
    ),
    "pw": (
        "Ink Sharing",
        "Higher: more ink flows each step between neighbouring hair clusters "
        "inside the brush (not bleeding on paper: see the paper's Ink Capacity)",
    ),
    "sm": (
        "Paper Grip",
        "Higher: the paper pushes back harder on a moving brush and drags the hair more",
    ),
    "ab": (
        "Absorbency",
        "Higher: the paper drinks the brush's ink faster, so strokes run dry sooner",
    ),
    "dry": ("Drying Speed", "Higher: wet ink on the paper dries faster"),
}
QUALITY_LABELS = {name: label for name, (label, _tip) in QUALITY_UI.items()}
PRESET_KINDS_SHOWN = ("brush", "paper", "ink", "quality")


def _overwrites(kind: str, p) -> str:
    """What choosing the preset sets, in the sidebar's words."""
    names = [QUALITY_LABELS[k] for k in p.data.get("quality", {}) if k in QUALITY_LABELS]
    if kind == "brush":
        hair = geometry_from_preset(p).hair_length_mm
        return f"hair length {hair:g} mm (the touching height) and " + ", ".join(names)
    if kind == "paper":
        return "paper colour, Ink Capacity, Fibre and " + ", ".join(names)
    if kind == "ink":
        return "Ink Colour, Ink Wetness and Dip Depth"
    return ", ".join(names)


def _preset_items(kind):
    items = []
    for i, name in enumerate(preset_names(kind)):
        p = load_preset(kind, name)
        tip = f"{p.description} Choosing it sets {_overwrites(kind, p)}".strip()
        items.append((name, p.label, tip, i))
    return items


# EnumProperty items must stay referenced from Python (Blender keeps no copy of the strings);
# read once here, so nothing in a draw() reads a preset file
ITEMS = {kind: _preset_items(kind) for kind in PRESET_KINDS_SHOWN}
PRESET_INFO = {(kind, it[0]): (it[1], it[2]) for kind, items in ITEMS.items() for it in items}
HAIR_LENGTH_MM = {
    name: geometry_from_preset(load_preset("brush", name)).hair_length_mm
    for name, *_ in ITEMS["brush"]
}


def preset_label(kind: str, name: str) -> str:
    return PRESET_INFO.get((kind, name), (name, ""))[0]


def apply_quality_presets(st, brush: bool = True, paper: bool = True):
    """Copy the quality values that the chosen brush/paper presets define into the settings."""
    values = quality_from_presets(
        load_preset("brush", st.brush_preset) if brush else None,
        load_preset("paper", st.paper_preset) if paper else None,
    )
    for k, v in values.items():
        setattr(st.quality, k, v)


def apply_paper_preset(st):
    """The paper preset's colour, capacity, fibre and texture into the settings."""
    spec = paper_from_preset(load_preset("paper", st.paper_preset))
    st.paper_color = spec.color
    st.paper_capacity = spec.capacity
    st.paper_fibre = spec.fibre
    st.paper_texture = spec.texture


def apply_ink_preset(st):
    ink = ink_from_preset(load_preset("ink", st.ink_preset))
    st.ink_color = ink.color
    st.dip_wetness = ink.wetness
    st.dip_depth = ink.depth


def hair_length(st) -> float:
    return geometry_from_preset(load_preset("brush", st.brush_preset)).hair_length_mm
