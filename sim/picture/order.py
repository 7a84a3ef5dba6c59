# SPDX-License-Identifier: GPL-3.0-or-later
"""Direction and writing order of the strokes read off a picture, as calligraphy is taught (see
``imitate``, step 3): each stroke running the way it is written (``orient``), side-by-side
parts left to right, and in each the strokes top to bottom, left to right, with the rules of
which stroke comes first (``writing_order``)."""

from __future__ import annotations

import numpy as np

from ..core import exact
from ..image import morph as M
from .strokes import Stroke

FLAT = exact.sin(np.radians(30.0)) / exact.cos(
    np.radians(30.0)
)  # a stroke whose chord rises less than this lies flat
STEEP = exact.sin(np.radians(60.0)) / exact.cos(np.radians(60.0))
THICKER = 1.3  # an end this much thicker than the other is where the brush entered
POINTED = 1.8  # a flat stroke must end this much thinner to be a 撇 (a 横 ends pressed)
OVERHANG = 0.15  # of a piece of ink's width at either side: a tip reaching over, not a part
MIN_SIDE = 0.2  # a side-by-side part of a character holds at least this share of its ink
ROW = 0.05  # strokes starting within this share of the em box of each other are one row


# ------------------------------------------------------------------- direction and order
def _end_widths(s: Stroke) -> tuple[float, float]:
    """Mean half-width over 10-30 % of the way in from each end."""
    n = len(s.radius)
    a, b = max(int(0.1 * n), 0), max(int(0.3 * n), 1)
    return float(s.radius[a:b].mean()), float(s.radius[n - b : n - a].mean())


def orient(s: Stroke) -> Stroke:
    """The stroke running the way it is written (see the module's docstring)."""
    d = s.pts[-1] - s.pts[0]
    dx, dy = float(d[0]), float(d[1])
    first, last = _end_widths(s)
    if abs(dy) <= STEEP * abs(dx) and dx * dy < 0:  # rises to the right (image y is down)
        low_left_first = dx > 0
        w_ll, w_ur = (first, last) if low_left_first else (last, first)
        if w_ll > THICKER * w_ur:  # a 提: entered at the lower left
            forward = low_left_first
        elif w_ur > (POINTED if abs(dy) <= FLAT * abs(dx) else THICKER) * w_ll:  # a 撇
            forward = not low_left_first
        else:  # flat: left to right; steeper: top to bottom
            forward = (dx > 0) if abs(dy) <= FLAT * abs(dx) else (dy > 0)
    elif abs(dy) <= FLAT * abs(dx):
        forward = dx > 0
    else:
        forward = dy > 0
    if forward:
        return s
    return Stroke(s.pts[::-1].copy(), s.radius[::-1].copy(), s.through, s.touches, s.joints)


def is_flat(s: Stroke) -> bool:
    d = s.pts[-1] - s.pts[0]
    return abs(float(d[1])) <= FLAT * abs(float(d[0]))


def ends_flat(s: Stroke) -> bool:
    """A stroke that comes down and turns into a horizontal at its foot (竖折, the 凵 of 山 and
    出): its first third stands, its last third lies flat."""
    k = max(len(s.pts) // 3, 1)
    if len(s.pts) < 6:
        return False
    d0, d1 = s.pts[k] - s.pts[0], s.pts[-1] - s.pts[-1 - k]
    return abs(float(d0[1])) > STEEP * abs(float(d0[0])) and abs(float(d1[1])) <= FLAT * float(
        d1[0]
    )


def _lies_flat(s: Stroke) -> bool:
    return is_flat(s) or ends_flat(s)


def _must_precede(a: Stroke, b: Stroke) -> bool:
    """A flat stroke ``a`` (or a 竖折's horizontal) comes before a standing one ``b`` that
    crosses it or starts on it; ``b`` comes first when it ends on ``a``. A 竖折 comes before
    the standing stroke its horizontal runs into at its end (凵's right side)."""
    if not _lies_flat(a) or is_flat(b):
        return False
    if a.through & b.through:  # a crossing anywhere decides, whatever else b touches
        return True
    on_a = sorted(a.through & b.touches)
    if on_a:
        return any(_starts_at(b, node) for node in on_a)
    if ends_flat(a) and not ends_flat(b):
        return any(not _starts_at(a, node) for node in a.touches if node in b.through | b.touches)
    return False


def _cores(mask: np.ndarray) -> np.ndarray:
    """The ink without the outer OVERHANG of each separate piece's width on either side: the
    tip of 亻's 丿 reaching over the start of 也 does not join the two parts."""
    lab, k = M.label(mask)
    if k == 0:
        return mask
    cols = np.broadcast_to(np.arange(mask.shape[1]), mask.shape)[mask]
    ids = lab[mask]
    lo = np.full(k + 1, mask.shape[1])
    hi = np.full(k + 1, -1)
    np.minimum.at(lo, ids, cols)
    np.maximum.at(hi, ids, cols)
    cut = OVERHANG * (hi - lo)
    keep = (cols >= (lo + cut)[ids]) & (cols <= (hi - cut)[ids])
    out = np.zeros_like(mask)
    out[mask] = keep
    return out


def _sides(strokes: list, idx: list, mask: np.ndarray, x0: int, x1: int) -> list[list]:
    """The strokes ``idx`` in side-by-side parts, left to right: the ink between columns x0
    and x1 is cut at the widest column free of ink that leaves two strokes or more and a
    fifth of the ink or more on either side (亻 | 也), and each side is cut again."""
    weight = mask[:, x0:x1].sum(axis=0)
    inked = np.flatnonzero(weight)
    if len(idx) < 4 or inked.size == 0:
        return [idx]
    free = np.flatnonzero(weight[inked[0] : inked[-1]] == 0) + inked[0]
    mid = {i: float(strokes[i].pts[:, 0].mean()) - x0 for i in idx}
    best, total = None, weight.sum()
    for run in np.split(free, np.flatnonzero(np.diff(free) > 1) + 1) if free.size else []:
        cut = 0.5 * (run[0] + run[-1])
        left = [i for i in idx if mid[i] < cut]
        share = weight[: int(cut)].sum() / total
        ok = 2 <= len(left) <= len(idx) - 2 and MIN_SIDE <= share <= 1 - MIN_SIDE
        if ok and (best is None or len(run) > best[0]):
            best = (len(run), int(cut), left)
    if best is None:
        return [idx]
    _, cut, left = best
    right = [i for i in idx if i not in left]
    return _sides(strokes, left, mask, x0, x0 + cut) + _sides(strokes, right, mask, x0 + cut, x1)


def writing_order(strokes: list, n: int, mask: np.ndarray | None = None) -> list[int]:
    """Side-by-side parts of the character left to right (``_sides``, given the ink); in each,
    top to bottom, left to right (rows of ROW of the em box; a flat stroke first in its row),
    with ``_must_precede`` kept; a cycle of rules is broken by the top-left stroke."""
    k = len(strokes)
    side = np.zeros(k, dtype=int)
    if mask is not None:
        core = _cores(mask)
        for g, members in enumerate(_sides(strokes, list(range(k)), core, 0, mask.shape[1])):
            side[members] = g
    after = {i: set() for i in range(k)}
    for i in range(k):
        for j in range(k):
            if i != j and _must_precede(strokes[i], strokes[j]):
                after[j].add(i)
    for i in range(k):  # a stroke standing on a flat one goes before it
        for j in range(k):
            if i != j and _stands_on(strokes[i], strokes[j]):
                after[j].add(i)

    def key(i):
        x, y = strokes[i].pts[0]
        return (side[i], int(y // (ROW * n)), 0 if is_flat(strokes[i]) else 1, float(x))

    order, placed = [], set()
    while len(order) < k:
        free = [i for i in range(k) if i not in placed and after[i] <= placed]
        pick = min(free or [i for i in range(k) if i not in placed], key=key)
        order.append(pick)
        placed.add(pick)
    return order


def _starts_at(s: Stroke, node: int) -> bool:
    c = s.joints[node]
    return bool(np.linalg.norm(s.pts[0] - c, axis=-1) <= np.linalg.norm(s.pts[-1] - c, axis=-1))


def _stands_on(b: Stroke, a: Stroke) -> bool:
    """Standing stroke ``b`` comes before flat stroke ``a``: it ends on it (the foot of 王's
    vertical), or both start at one corner (口's left side before its top, also when the
    left side's 露锋 tip reaches on past the corner: ``strokes._tips``)."""
    if not _lies_flat(a) or is_flat(b) or ends_flat(b):
        return False
    for node in b.touches:
        if node in a.through and not _starts_at(b, node):
            return True
    for node in b.touches | b.through:  # b's pointed tip may reach on past the corner
        if node in a.touches and _starts_at(b, node) and _starts_at(a, node):
            return True
    return False
