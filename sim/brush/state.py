# SPDX-License-Identifier: GPL-3.0-or-later
"""The state of the brush's writing primitives (Sec. 3.2), declared once.

``FIELDS`` is the one table of what a key point and a writing primitive carry; creating the
free state, taking primitives (a split), snapshots, the active point's insertion (Eq. 13) and
the ink rows of the marks (Eq. 21) are all derived from it, so a new field is one new row.

Glossary of the paper's symbols used as field names:
- ``cc``: the key points P_i,1..n of a primitive's middle control axis (paper mm).
- ``sarc``: each key point's arc coordinate along the hair from the bottom control circle (mm);
  hair is inextensible, so a key point is a material point of the hair.
- ``wet``, ``col``: the ink a key point carries, wetness and colour as density (Eq. 3-4).
- ``wr``, ``cr``: the texture function's radiation mode for wetness and colour (Eq. 5).
- ``wv``, ``cv``: its vector mode, directions in the brush's frame (Eq. 5).
- ``a``, ``b``: the middle control ellipse's axes (mm); ``loc`` its place along the axis, as a
  share of it; ``eori`` its minor axis's direction in the brush frame (Eq. 6).
- ``tiplen``: the length of the tip control line (len, Sec. 5.4).
- ``stress``, ``gamma``: inner stress str and pressure (Eq. 10, 12).
- ``contact``: S_i of the last step, the area of the section's cut by the paper (Eq. 10), and
  ``sweep`` the fresh paper it passes over a second (its width across the motion times the
  speed): what the paper takes ink from (Eq. 15 with the ink the paper takes).
- ``hair_u``, ``bundle``, ``edge``, ``gap``: the primitive's hair bundles (``bristles``, a
  model addition): dry-brush draws (Eq. 27), ink shares, boundaries and dry gaps; ``moist``
  the wetness they feel on the paper.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..core.exact import matmul

CONTACT_EPS = 1e-6  # mm: a key point this close to psi is on the paper
BUNDLES = 20  # hair bundles across a primitive's section (``bristles``)
KEY = "key point"  # a field of every key point: (m, n, *shape)
PRIMITIVE = "primitive"  # a field of every primitive: (m, *shape)


class Field(NamedTuple):
    name: str
    per: str  # KEY or PRIMITIVE
    shape: tuple = ()  # trailing shape
    dtype: type = float
    fill: float = 0.0  # value in the free state (the brush sets the shape fields, Sec. 3.4)
    ink: bool = False  # a column of the ink rows (Eq. 21): carried to the marks
    brush_frame: bool = False  # a direction in the brush's frame (turned with it)


FIELDS = (
    Field("sarc", KEY),
    Field("cc", KEY, (3,)),
    # the ink rows' columns, in this order (ink_layout)
    Field("wet", KEY, ink=True),
    Field("col", KEY, (3,), ink=True),
    Field("wr", KEY, ink=True),
    Field("cr", KEY, ink=True),
    Field("wv", KEY, (3,), ink=True, brush_frame=True),
    Field("cv", KEY, (3,), ink=True, brush_frame=True),
    Field("a", PRIMITIVE),
    Field("b", PRIMITIVE),
    Field("loc", PRIMITIVE),
    Field("eori", PRIMITIVE, (3,)),
    Field("tiplen", PRIMITIVE),
    Field("gamma", PRIMITIVE),
    Field("stress", PRIMITIVE),
    Field("contact", PRIMITIVE),
    Field("sweep", PRIMITIVE),
    Field("hair_u", PRIMITIVE, (BUNDLES,)),  # each hair bundle's draw for Eq. 27 (bristles)
    Field("bundle", PRIMITIVE, (BUNDLES,), fill=1.0),  # each bundle's share of the ink
    Field("edge", PRIMITIVE, (BUNDLES - 1,)),  # where the bundles meet across the section
    Field("gap", PRIMITIVE, (BUNDLES,)),  # the share of each bundle's width that lays no ink
    Field("moist", PRIMITIVE),  # the wetness of the hair on the paper as the bundles feel it
    Field("lay", PRIMITIVE, (2,)),  # where a vertical brush at rest lays its hair
    Field("active", PRIMITIVE, dtype=int, fill=-1),  # the active point, -1 for none (Eq. 13)
    Field("touching", PRIMITIVE, dtype=bool, fill=False),  # the section reaches the paper
)
INK = tuple(f for f in FIELDS if f.ink)
# the whole brush's pose, kept with the fields in snapshots (``trail``: the recent path of the
# hair's contact with the paper, ``bristles``)
POSE = ("travel", "travel_from", "B", "R", "trail")


def _width(f: Field) -> int:
    return int(np.prod(f.shape, dtype=int))


def ink_layout() -> dict:
    """The columns of every ink field in the ink rows (..., INK_WIDTH), in FIELDS order."""
    out, at = {}, 0
    for f in INK:
        out[f.name] = slice(at, at + _width(f))
        at += _width(f)
    return out


INK_FIELDS = ink_layout()
INK_WIDTH = sum(_width(f) for f in INK)


def ink_field(rows, name: str) -> np.ndarray:
    """One field of a stacked ink array (..., INK_WIDTH); scalars lose their last axis."""
    out = rows[..., INK_FIELDS[name]]
    return out[..., 0] if out.shape[-1] == 1 else out


def blank(brush, m: int):
    """Every field of m primitives at its free-state fill value."""
    for f in FIELDS:
        lead = (m, brush.n) if f.per == KEY else (m,)
        setattr(brush, f.name, np.full(lead + f.shape, f.fill, dtype=f.dtype))
    brush.travel_from = brush.B[:2].copy()  # where the leash of ``travel`` is held (dynamics)


def take_primitives(brush, src):
    """Keep primitives ``src`` (an index array: repeats copy a primitive)."""
    for f in FIELDS:
        setattr(brush, f.name, getattr(brush, f.name)[src])


def key_point_fields(exclude=()) -> tuple:
    """The names of the key points' fields, less ``exclude``."""
    return tuple(f.name for f in FIELDS if f.per == KEY and f.name not in exclude)


def snapshot(brush) -> dict:
    snap = {k: np.array(getattr(brush, k), copy=True) for k in _SNAPSHOT}
    snap["state"] = brush.state
    snap["splits"] = brush.splits
    return snap


def restore(brush, snap: dict):
    for k in _SNAPSHOT:
        setattr(brush, k, np.array(snap[k], copy=True))
    brush.state = snap["state"]
    brush.splits = snap["splits"]


_SNAPSHOT = tuple(f.name for f in FIELDS) + POSE


def ink_keys(brush) -> np.ndarray:
    """Every key point's ink fields stacked into one array (m, n, INK_WIDTH), in INK_FIELDS
    order; vector-mode fields turned from the brush frame into paper coordinates."""
    parts = []
    for f in INK:
        v = getattr(brush, f.name)
        if f.brush_frame:
            v = matmul(v, brush.R.T)
        parts.append(v if f.shape else v[..., None])
    return np.concatenate(parts, axis=2)
