# SPDX-License-Identifier: GPL-3.0-or-later
"""Imitating a picture (Sec. 9, "automatic imitation"): from a picture of writing to a
recording of the brush writing it.

1. The ink (``picture_ink``): the picture fitted into the em box (small writing framed), the
   paper's uneven level divided out, a red seal taken for paper, Otsu's threshold, specks and
   pin-holes cleaned.
2. The strokes (``picture_strokes``): the ink's skeleton as chains between junctions, spurs
   pruned, chains that continue each other by direction joined across junctions; each with its
   half-width along it (the distance transform).
3. Direction and order (here), as calligraphy is taught: a stroke runs left to right when it
   lies flat, else top to bottom, except that a stroke that rises to the right starts at its
   thicker end (where the brush entered: a rising 提 or a flat 撇, whose tail is a point);
   side-by-side parts of the character go left to right, and in each the strokes top to
   bottom, left to right, a horizontal before the stroke that crosses it or hangs from it, and
   after one that stands on it.
4. Character data (here): each stroke's median, and as its outline the picture's own ink round
   it (the ink within its width of its median, the rest of the ink to the nearest stroke),
   traced into polygons; so ``imitate.write_character`` presses as wide as the picture's
   strokes and practises each stroke against the picture's ink.

Everything here is numpy only (it runs in Blender)."""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..image import morph as M
from ..writing.hanzi import MAX_STROKES
from ..writing.outline import EM, TOP, discs
from .ink import Ink, PictureError, find_ink, grey_of, load_picture
from .strokes import Stroke, find_strokes

FLAT = np.tan(np.radians(30.0))  # a stroke whose chord rises less than this lies flat
STEEP = np.tan(np.radians(60.0))
THICKER = 1.3  # an end this much thicker than the other is where the brush entered
POINTED = 1.8  # a flat stroke must end this much thinner to be a 撇 (a 横 ends pressed)
OVERHANG = 0.15  # of a piece of ink's width at either side: a tip reaching over, not a part
MIN_SIDE = 0.2  # a side-by-side part of a character holds at least this share of its ink
ROW = 0.05  # strokes starting within this share of the em box of each other are one row
TUBE = (1.0, 0.5)  # a stroke's own ink: within its half-width of its median, plus pixels
MEDIAN_EPS = 2.0  # px at 512: the median simplified this closely
OUTLINE_EPS = 0.6  # px: the outline's polygons simplified this closely
MAX_OUTLINE_POINTS = 1500  # per stroke (sim.hanzi takes up to 2000)
MAX_MEDIAN_POINTS = 200  # per stroke (sim.hanzi takes up to 256)
BLOT_CURL = np.radians(35.0)  # a median's end that turns more than this inside its blot
PIECE_GAP = 0.02  # of the em box: a free band this wide may part two columns or characters
SQUARE = 1.25  # a character is at most this times as tall as its column is wide
NARROW = 0.5  # a column narrower than this share of the widest is part of its neighbour
PIECE_FILL = 0.8  # a character fills this share of its own square (as in a font's em box)
PASSES = 5  # practice passes per stroke: the picture's ink is the target (3: IoU 0.01 lower)
MAX_DETAIL = 2048  # px a side: a picture is read at most this fine (Blender's Detail, the CLI)


@dataclass
class Imitation:
    """What was read off a picture: its ink, the strokes in writing order (each running the
    way it is written), each stroke's own ink, the character data for the writer, and the
    seconds the reading took."""

    ink: Ink
    strokes: list
    regions: list
    char: dict
    seconds: float


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
    return bool(np.linalg.norm(s.pts[0] - c) <= np.linalg.norm(s.pts[-1] - c))


def _stands_on(b: Stroke, a: Stroke) -> bool:
    """Standing stroke ``b`` comes before flat stroke ``a``: it ends on it (the foot of 王's
    vertical), or both start at one corner (口's left side before its top)."""
    if not _lies_flat(a) or is_flat(b) or ends_flat(b):
        return False
    for node in b.touches:
        if node in a.through and not _starts_at(b, node):
            return True
        if node in a.touches and _starts_at(b, node) and _starts_at(a, node):
            return True
    return False


# ----------------------------------------------------------------- each stroke's own ink
def stroke_regions(strokes: list, mask: np.ndarray) -> list[np.ndarray]:
    """Each stroke's own ink: the ink within its width of its median (strokes overlap at
    crossings), and the ink no stroke reaches so goes to the nearest stroke."""
    n = mask.shape[0]
    tubes = [discs(s.pts + 0.5, s.radius * TUBE[0] + TUBE[1], n) & mask for s in strokes]
    rest = mask & ~np.any(tubes, axis=0) if tubes else mask
    if rest.any():
        owner = np.zeros(mask.shape, dtype=np.int32)
        for i, s in enumerate(strokes):
            iy = np.clip(np.round(s.pts[:, 1]).astype(int), 0, n - 1)
            ix = np.clip(np.round(s.pts[:, 0]).astype(int), 0, n - 1)
            owner[iy, ix] = i + 1
        _, ry, rx = M.nearest_feature(owner > 0)
        near = owner[np.maximum(ry, 0), np.maximum(rx, 0)]
        for i in range(len(strokes)):
            tubes[i] |= rest & (near == i + 1)
    return tubes


def trace_outline(region: np.ndarray) -> list[np.ndarray]:
    """The boundary of a pixel region as closed polygons along the pixels' edges (image
    pixels, x right, y down); filled even-odd by pixel centres they give the region back."""
    r = np.pad(np.asarray(region, dtype=bool), 1)
    edges = []
    for (dy, dx), (a, b) in (
        ((-1, 0), ((0, 0), (1, 0))),  # top edge, left to right
        ((0, 1), ((1, 0), (1, 1))),  # right edge, downwards
        ((1, 0), ((1, 1), (0, 1))),  # bottom edge, right to left
        ((0, -1), ((0, 1), (0, 0))),  # left edge, upwards
    ):
        ys, xs = np.nonzero(r & ~np.roll(r, (-dy, -dx), axis=(0, 1)))
        for y, x in zip(ys.tolist(), xs.tolist(), strict=True):
            edges.append(((x + a[0] - 1, y + a[1] - 1), (x + b[0] - 1, y + b[1] - 1)))
    out_of: dict = {}
    for e in edges:
        out_of.setdefault(e[0], []).append(e[1])
    polys = []
    while out_of:
        start = next(iter(out_of))
        loop, cur = [start], start
        while True:
            nxt = out_of[cur].pop()
            if not out_of[cur]:
                del out_of[cur]
            if nxt == start:
                break
            loop.append(nxt)
            cur = nxt
        if len(loop) >= 3:
            polys.append(np.array(loop, dtype=np.float64))
    return polys


def simplify(poly: np.ndarray, eps: float, closed: bool = True) -> np.ndarray:
    """Douglas-Peucker on a closed polygon (or an open polyline): its points within ``eps``
    of the original."""
    n = len(poly)
    if n <= 3:
        return poly
    far = int(np.argmax(np.linalg.norm(poly - poly[0], axis=1))) if closed else n - 1
    keep = np.zeros(n, dtype=bool)
    keep[[0, far]] = True
    stack = [(0, far), (far, n)] if closed else [(0, n - 1)]
    while stack:
        i, j = stack.pop()
        a, b = poly[i], poly[j % n]
        if j - i < 2:
            continue
        seg = poly[i + 1 : j]
        ab = b - a
        L = float(np.linalg.norm(ab))
        if L < 1e-9:
            d = np.linalg.norm(seg - a, axis=1)
        else:
            d = np.abs(ab[0] * (seg[:, 1] - a[1]) - ab[1] * (seg[:, 0] - a[0])) / L
        k = int(np.argmax(d))
        if d[k] > eps:
            m = i + 1 + k
            keep[m] = True
            stack += [(i, m), (m, j)]
    return poly[keep]


# -------------------------------------------------------------------- character data
def _to_data(pts: np.ndarray, n: int) -> np.ndarray:
    return np.stack([pts[:, 0] * EM / n, TOP - pts[:, 1] * EM / n], axis=1)


def _svg(polys: list, n: int) -> str:
    parts = []
    for p in polys:
        d = _to_data(p, n)
        parts.append("M " + " L ".join(f"{x:.1f} {y:.1f}" for x, y in d) + " Z")
    return " ".join(parts)


def outline_svg(region: np.ndarray, n: int) -> str:
    """A stroke's own ink as an SVG path in data units, within the point budget."""
    polys = trace_outline(region)
    eps = OUTLINE_EPS
    while True:
        simple = [q for q in (simplify(p, eps) for p in polys) if len(q) >= 3]
        if sum(len(q) for q in simple) <= MAX_OUTLINE_POINTS or eps > 8:
            return _svg(simple, n)
        eps *= 1.6


def _straight_start(pts: np.ndarray, radius: np.ndarray) -> np.ndarray:
    """The median's start straightened inside the blot where the brush landed: the skeleton of
    a round blot (the head of the scan's 永 撇) curls within the blot's half-width of the end,
    and the writer takes such a curl for a sharp turn (it lifts and lands again there: a false
    折 and a second blot). Where the heading within the blot differs from the stroke's heading
    beyond it by more than BLOT_CURL, the median runs straight on along the stroke's heading
    there instead. (The stroke's last end is left alone: a hook turns inside its foot.)"""
    p = pts.astype(np.float64).copy()
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])
    reach = float(radius[: max(len(radius) // 4, 1)].max())
    i = int(np.searchsorted(s, reach))
    j = int(np.searchsorted(s, s[min(i, len(s) - 1)] + reach))
    if i < 2 or j >= len(p) - 1 or s[-1] < 3.0 * reach:
        return p
    beyond, inside = p[i] - p[j], p[0] - p[i]
    cos = beyond @ inside / max(float(np.linalg.norm(beyond) * np.linalg.norm(inside)), 1e-9)
    if np.arccos(np.clip(cos, -1.0, 1.0)) > BLOT_CURL:
        u = beyond / max(float(np.linalg.norm(beyond)), 1e-9)
        p[:i] = p[i] + u * (s[i] - s[:i])[:, None]
    return p


def _median(s: Stroke, n: int) -> list:
    """The stroke's centre line as a polyline within MEDIAN_EPS of it (the skeleton's jitter
    gone, its corners kept, its start straight inside its blot), in data units."""
    eps = MEDIAN_EPS * n / 512
    line = _straight_start(s.pts, s.radius)
    pts = simplify(line, eps, closed=False)
    while len(pts) > MAX_MEDIAN_POINTS:
        eps *= 1.5
        pts = simplify(line, eps, closed=False)
    return [[round(float(x), 1), round(float(y), 1)] for x, y in _to_data(pts, n)]


def read_strokes(ink: Ink) -> tuple[list, list, dict]:
    """The strokes of a picture's ink in writing order, their own ink, and the character data
    for the writer."""
    n = ink.mask.shape[0]
    found = [orient(s) for s in find_strokes(ink.mask)]
    found = [s for s in found if len(s.pts) >= 2 and s.radius.max() > 0]
    if not found:
        raise PictureError("no strokes found in the picture's ink")
    if len(found) > MAX_STROKES:
        raise PictureError(
            f"the picture's ink makes {len(found)} strokes; at most {MAX_STROKES} (one character)"
        )
    strokes = [found[i] for i in writing_order(found, n, ink.mask)]
    regions = stroke_regions(strokes, ink.mask)
    keep = [i for i, r in enumerate(regions) if r.sum() >= 4]
    if not keep:  # every stroke's own ink is a few pixels: nothing the writer could write
        raise PictureError("no strokes found in the picture's ink")
    strokes, regions = [strokes[i] for i in keep], [regions[i] for i in keep]
    char = {
        "strokes": [outline_svg(r, n) for r in regions],
        "medians": [_median(s, n) for s in strokes],
    }
    return strokes, regions, char


# ---------------------------------------------------------- a piece of several characters
def _runs(weight: np.ndarray, gap: int) -> list[tuple[int, int]]:
    """The inked runs of a projection, parted where it is free for ``gap`` or more."""
    inked = np.flatnonzero(weight > 0)
    if inked.size == 0:
        return []
    cut = np.flatnonzero(np.diff(inked) > gap)
    starts = np.concatenate([[inked[0]], inked[cut + 1]])
    ends = np.concatenate([inked[cut], [inked[-1]]]) + 1
    return [(int(a), int(b)) for a, b in zip(starts, ends, strict=True)]


def piece_boxes(mask: np.ndarray) -> list[tuple[int, int, int, int]]:
    """The characters of a piece, (y0, y1, x0, x1) each, in the traditional reading order:
    columns right to left (parted by free bands of PIECE_GAP; a column narrower than NARROW of
    the widest, such as a 亻 standing apart, is part of its neighbour), and in each column
    top to bottom: free bands part characters where the character above would otherwise grow
    taller than SQUARE times the column's width (三's gaps stay inside one character)."""
    gap = max(int(PIECE_GAP * mask.shape[0]), 2)
    cols = _runs(mask.sum(axis=0), gap)
    if not cols:
        return []
    widest = max(b - a for a, b in cols)
    merged: list[tuple[int, int]] = []
    for a, b in cols:
        if merged and min(b - a, merged[-1][1] - merged[-1][0]) < NARROW * widest:
            merged[-1] = (merged[-1][0], b)
        else:
            merged.append((a, b))
    boxes = []
    for x0, x1 in reversed(merged):
        chars: list[tuple[int, int]] = []
        for y0, y1 in _runs(mask[:, x0:x1].sum(axis=1), gap):
            if chars and y1 - chars[-1][0] <= SQUARE * (x1 - x0):
                chars[-1] = (chars[-1][0], y1)
            else:
                chars.append((y0, y1))
        boxes += [(y0, y1, x0, x1) for y0, y1 in chars]
    return boxes


def _character_ink(ink: Ink, box, n: int) -> Ink:
    """One character of a piece on its own n x n em box (filling PIECE_FILL of it): the
    piece's darkness round it resampled, thresholded as the piece's."""
    from .ink import _clean

    y0, y1, x0, x1 = box
    side = int(np.ceil(max(y1 - y0, x1 - x0) / PIECE_FILL))
    cy, cx = (y0 + y1) // 2, (x0 + x1) // 2
    dark = np.zeros((side, side))
    keep = np.zeros(ink.mask.shape, dtype=bool)
    keep[y0:y1, x0:x1] = True
    src = np.where(keep, ink.darkness, 0.0)
    ya, xa = cy - side // 2, cx - side // 2
    yb, xb = ya + side, xa + side
    H, W = src.shape
    dark[max(-ya, 0) : side - max(yb - H, 0), max(-xa, 0) : side - max(xb - W, 0)] = src[
        max(ya, 0) : min(yb, H), max(xa, 0) : min(xb, W)
    ]
    big = M.resize(dark, n, n)
    return Ink(_clean(big > ink.threshold), big, ink.threshold, ink.separation)


def _placed(char: dict, cell: tuple[float, float, float]) -> dict:
    """A character's data (its own em box) moved into a cell of the sheet's em box: (x, y of
    the cell's top left corner from the em box's top left, side), in data units."""
    import re

    x0, y0, k = cell[0], cell[1], cell[2] / EM

    def at(x: float, y: float) -> tuple[float, float]:
        return x0 + x * k, TOP - (y0 + (TOP - y) * k)

    def svg(path: str) -> str:
        def pair(m):
            x, y = at(float(m.group(1)), float(m.group(2)))
            return f"{x:.1f} {y:.1f}"

        return re.sub(r"(-?[\d.]+) (-?[\d.]+)", pair, path)

    return {
        "strokes": [svg(p) for p in char["strokes"]],
        "medians": [[[round(v, 1) for v in at(x, y)] for x, y in m] for m in char["medians"]],
    }


def read_piece(ink: Ink) -> tuple[list, list, dict] | None:
    """A piece of several characters (``piece_boxes``): each read on its own em box, then set
    in its own square of the sheet - columns right to left, top to bottom - and written in that
    order. None when the picture holds one character."""
    n = ink.mask.shape[0]
    boxes = piece_boxes(ink.mask)
    if len(boxes) < 2:
        return None
    col_of = {}
    for y0, y1, x0, x1 in boxes:
        col_of.setdefault((x0, x1), []).append((y0, y1))
    cols, rows = len(col_of), max(len(v) for v in col_of.values())
    side = EM / max(cols, rows)
    left, top = (EM - cols * side) / 2, (EM - rows * side) / 2
    strokes, regions, medians, outlines = [], [], [], []
    for c, (span, chars) in enumerate(col_of.items()):
        for r, (y0, y1) in enumerate(chars):
            s, reg, char = read_strokes(_character_ink(ink, (y0, y1, *span), n))
            placed = _placed(char, (left + (cols - 1 - c) * side, top + r * side, side))
            strokes += s
            regions += reg
            medians += placed["medians"]
            outlines += placed["strokes"]
    if len(outlines) > MAX_STROKES:
        raise PictureError(
            f"the piece's {len(boxes)} characters make {len(outlines)} strokes; at most "
            f"{MAX_STROKES} on one sheet"
        )
    return strokes, regions, {"strokes": outlines, "medians": medians}


def read_picture(source, n: int = 512, name: str | None = None, piece: bool = False) -> Imitation:
    """Read a picture (a PNG path, or an image array (H, W[, C])) into an Imitation on an
    n x n em box (n at most MAX_DETAIL); with ``piece``, a picture of several characters in
    columns is read as such (``read_piece``: each character in its own square). PictureError
    (or PNGError) for a picture this cannot imitate."""
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 0 < n <= MAX_DETAIL:
        raise PictureError(f"a picture is read at 1 to {MAX_DETAIL} px a side, got {n!r}")
    t0 = time.perf_counter()
    if isinstance(source, (str, bytes)) or hasattr(source, "__fspath__"):
        grey = load_picture(source)
        name = name or str(source)
    else:
        grey = grey_of(source, name or "the picture")
    ink = find_ink(grey, n, name or "the picture")
    found = read_piece(ink) if piece else None
    strokes, regions, char = found if found is not None else read_strokes(ink)
    if found is not None:  # the sheet's ink: each character in its square
        from ..writing.outline import rasterise

        sheet = rasterise(char, n)
        ink = Ink(sheet, sheet.astype(np.float64), 0.5, ink.separation)
    return Imitation(ink, strokes, regions, char, time.perf_counter() - t0)


def imitate(
    source,
    template,
    n_px: int = 512,
    size_mm: float | None = None,
    passes: int = PASSES,
    progress=None,
    px_per_mm: float | None = None,
    response=None,
    piece: bool = False,
):
    """Read a picture and write it with the brush (``imitate.write_character``: press from the
    picture's widths, practice passes against the picture's own ink) on an n_px sheet; the
    picture is read on an em box of n_px, at most MAX_DETAIL, px a side (the Imitation's ink is
    at that size). Returns the recording, the response, the finished simulation and the
    Imitation."""
    from ..writing.writer import write_character

    if progress is not None:
        progress(0.0, "reading the picture")
    im = read_picture(source, min(n_px, MAX_DETAIL), piece=piece)  # the writing is n_px
    if progress is not None:
        progress(0.05, f"{len(im.strokes)} strokes found; writing")

    def writing(frac, *details):
        if progress is not None:
            progress(0.05 + 0.95 * frac, *details)

    rec, resp, sim = write_character(
        im.char,
        n_px,
        template,
        size_mm=size_mm,
        response=response,
        passes=passes,
        progress=writing,
        px_per_mm=px_per_mm,
    )
    return rec, resp, sim, im


def ink_on(mask: np.ndarray, n: int) -> np.ndarray:
    """A square mask (the ink read off a picture) on an n x n grid, each pixel the one under
    its centre (the ink read at MAX_DETAIL against a finer sheet)."""
    idx = ((np.arange(n) + 0.5) * len(mask) / n).astype(np.int64)
    return mask[idx[:, None], idx[None, :]]


# ------------------------------------------------------------------ against known data
def order_agreement(found: dict, known: dict, n: int = 512) -> dict:
    """How the strokes read off a picture agree with the character's known strokes: each found
    stroke is matched to the known stroke whose outline holds most of its median; ``pairs``
    is the share of pairs of found strokes (matched to different known ones) written in the
    known order, ``directions`` the share of matched strokes running the known way, ``same``
    whether the found strokes are the known ones in the known order."""
    from ..writing.outline import fill, resample, stroke_polygons, to_image

    masks = [fill([to_image(p, n) for p in polys], n) for polys in stroke_polygons(known)]
    match, runs = [], []
    for med in found["medians"]:
        pts = to_image(resample(np.array(med, dtype=float), 4.0)[0], n)
        iy = np.clip(pts[:, 1].astype(int), 0, n - 1)
        ix = np.clip(pts[:, 0].astype(int), 0, n - 1)
        share = [float(m[iy, ix].mean()) for m in masks]
        k = int(np.argmax(share))
        match.append(k if share[k] >= 0.5 else -1)
        kp, s = resample(np.array(known["medians"][k], dtype=float), 4.0)
        ends = np.array([med[0], med[-1]], dtype=float)
        near = np.argmin(np.linalg.norm(kp[None] - ends[:, None], axis=2), axis=1)
        runs.append(s[near[1]] > s[near[0]])
    pairs = [
        (match[i] < match[j])
        for i in range(len(match))
        for j in range(i + 1, len(match))
        if match[i] >= 0 and match[j] >= 0 and match[i] != match[j]
    ]
    matched = [r for r, m in zip(runs, match, strict=True) if m >= 0]
    return {
        "found": len(match),
        "known": len(masks),
        "pairs": float(np.mean(pairs)) if pairs else 1.0,
        "directions": float(np.mean(matched)) if matched else 0.0,
        "same": match == list(range(len(masks))),
    }
