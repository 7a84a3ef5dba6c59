# SPDX-License-Identifier: GPL-3.0-or-later
"""The ink a brush carries: dipping (Sec. 3.5, Eq. 7-8) and the ink at the axis points of the
sweep surface's rows (Sec. 3.2.3, Eq. 21), from which the marks take every pixel's ink.

A key point's ink information (Eq. 3-5): wetness ``wet``, colour ``col`` as density (0 is the
paper's colour), and the ink texture function that varies it across the section - radiation
mode ``wr``, ``cr`` (per millimetre from the axis) and vector mode ``wv``, ``cv`` (per
millimetre along a direction of the brush's frame), for wetness and colour. The ink rows stack
these fields as columns, laid out by ``INK_FIELDS`` (``brush_state``)."""

from __future__ import annotations

import numpy as np

from ..core.params import InkSpec
from .state import INK_FIELDS, ink_keys

# the texture function's fields (Eq. 5), named as InkSpec names them
TEXTURE_NAMES = ("wr", "cr", "wv", "cv")
# the ink rows' columns a pixel takes from V^ (wet, col) and those of the texture function
LOAD = slice(INK_FIELDS["wet"].start, INK_FIELDS["col"].stop)
TEXTURE = slice(INK_FIELDS["wr"].start, INK_FIELDS["cv"].stop)


def dip(brush, ink: InkSpec, depth: float | None = None, color=None, wetness=None):
    """Dipping state (Sec. 3.5, Eq. 7-8). The key points within ``depth`` (a fraction of the
    hair length, from the tip) are soaked; the others interpolate linearly toward the dry,
    paper-coloured first key point. Dipping also re-gathers split hair into one primitive and
    restores the point (paper's future work: merging, multiple and partial dipping): the old
    load is kept where it is wetter than the new one."""
    depth = ink.depth if depth is None else float(depth)
    rgb = np.asarray(ink.color if color is None else color, dtype=float)
    wetness = ink.wetness if wetness is None else float(wetness)
    old_wet = brush.wet.mean(axis=0)
    old_col = brush.col.mean(axis=0)
    brush._free_state(1, a=np.sqrt(4.0 * brush.hair_area() / np.pi))
    brush.place(np.r_[brush.B, 0.0, 0.0, 0.0])
    # ink colour as density: 0 is the paper's colour (Eq. 7 "col_P1 = 0 is pure white")
    ink_col = 1.0 - np.clip(rgb, 0.0, 1.0)
    s = brush.sarc[0]
    soaked = s >= (1.0 - depth) * brush.L - 1e-9
    soaked[0] = False
    if not soaked.any():
        soaked[-1] = True
    k = int(np.argmax(soaked))
    dist_k = s[k] - s[0]  # |cc_k - cc_1| on the straight free axis
    frac = np.clip((s - s[0]) / max(dist_k, 1e-9), 0.0, 1.0)
    new_col = np.where(soaked[:, None], ink_col, frac[:, None] * ink_col)  # Eq. 7
    new_wet = np.where(soaked, wetness, frac * wetness)  # Eq. 8
    new_col[0] = 0.0
    new_wet[0] = 0.0
    # multiple dipping: soaked hair takes the new ink, the rest keeps the wetter load
    keep_old = (~soaked) & (old_wet > new_wet)
    tot = np.maximum(old_wet + new_wet, 1e-12)
    mix_col = (old_col * old_wet[:, None] + new_col * new_wet[:, None]) / tot[:, None]
    brush.col[0] = np.where(keep_old[:, None], mix_col, new_col)
    brush.wet[0] = np.where(keep_old, old_wet, new_wet)
    for name in TEXTURE_NAMES:  # the ink's texture function (Eq. 5)
        getattr(brush, name)[0] = getattr(ink, name)
    brush.state = "dipping"


def rows_ink(brush, sec) -> np.ndarray:
    """Ink information at the surface rows' axis points V^ (Eq. 21): distance-weighted linear
    interpolation between the two key points that bracket each row along the axis. Returns
    (m, Ns, INK_WIDTH), the fields laid out as INK_FIELDS says."""
    return interpolate_rows(brush.layout.grid_s, sec.params, ink_keys(brush))


def interpolate_rows(s, t, keys) -> np.ndarray:
    """Eq. 21 at rows ``s`` (Ns,) of primitives whose key points lie at axis parameters ``t``
    (m, n) and carry ``keys`` (m, n, INK_WIDTH) (``ink_keys``). Each primitive's rows are its
    own: the primitives of many steps stacked give each step's rows, bit for bit."""
    m, n = t.shape
    j = np.clip(np.sum(t[:, None, :] <= s[None, :, None], axis=2) - 1, 0, n - 2)  # (m, Ns)
    t0 = np.take_along_axis(t, j, 1)
    t1 = np.take_along_axis(t, j + 1, 1)
    w1 = np.clip((s[None, :] - t0) / np.maximum(t1 - t0, 1e-12), 0.0, 1.0)
    w0 = 1.0 - w1
    jj = j[..., None]
    return w0[..., None] * np.take_along_axis(keys, jj, 1) + w1[..., None] * (
        np.take_along_axis(keys, jj + 1, 1)
    )


def brush_load(brush) -> float:
    """The ink the brush holds: its key points' wetness, averaged with each primitive weighted
    by its hair (the area of its middle ellipse, Sec. 5.3). (A measure beyond the paper: the
    writer and a work dip again by it.)"""
    hair = np.asarray(brush.a) * np.asarray(brush.b)
    return float(np.sum(brush.wet.mean(axis=1) * hair) / max(float(hair.sum()), 1e-12))


def full_load(template) -> float:
    """The load of the brush right after a full dip in the template recording's ink."""
    from .primitive import HairyBrush

    q, geometry, _, ink = template.resolve()
    brush = HairyBrush(geometry, q, np.random.Generator(np.random.PCG64(0)))
    brush.dip(ink)
    return brush_load(brush)
