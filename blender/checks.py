# SPDX-License-Identifier: GPL-3.0-or-later
"""The scene's settings read and checked: the brush and paper objects, settings that must be
numbers, and the paper's size in pixels against the engine's limits and the free memory. Every
problem an operator reports to the user is one of ``USER_ERRORS``."""

from __future__ import annotations

import math
import os

from ..sim import surface as surf
from ..sim.core.params import MAX_PAPER_PIXELS, MAX_PAPER_SIDE_PX, ParameterError, QualityParams
from ..sim.core.recording import RecordingError
from ..sim.engine.timeline import DEFAULT_BUDGET_BYTES as SNAPSHOT_BUDGET_BYTES

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
    "paint_angle_step": "Angle Step",
    "paper_capacity": "Ink Capacity",
    "paper_fibre": "Fibre",
    "paper_texture": "Texture",
    "paper_color": "Paper Colour",
    "ink_color": "Ink Colour",
}


def check_settings(st):
    """One clear message for a setting that is not a number (a colour: any of its channels)."""
    for name, label in FINITE_SETTINGS.items():
        value = getattr(st, name)
        if not all(math.isfinite(v) for v in (value if hasattr(value, "__len__") else [value])):
            raise UserError(f"{label} is not a number: set it again in the sidebar")
    for name in QualityParams.names():
        if not math.isfinite(getattr(st.quality, name)):
            raise UserError(f"Quality value '{name}' is not a number: set it again")


def check_number(value: float, label: str, hint: str = "set it again") -> float:
    """``value`` if it is a finite number, else UserError naming ``label`` (an operator's own
    property, which a script or a redo panel can set to NaN)."""
    if not math.isfinite(value):
        raise UserError(f"{label} is not a number: {hint}")
    return value


def quality_values(st) -> dict:
    """The scene's eleven quality values by name (a plain function, not a method of the
    PropertyGroup: Blender 4.2 crashes at exit when a PropertyGroup has methods)."""
    return {n: float(getattr(st.quality, n)) for n in QualityParams.names()}


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
