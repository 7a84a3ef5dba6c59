# SPDX-License-Identifier: GPL-3.0-or-later
"""The brush's dynamic adjustments (Sec. 5): every time slice, the bottom control circle moves
to the virtual position and the writing primitives follow - the active point (Eq. 13),
deformation and recovery (Sec. 5.2, Eq. 14), inner stress and pressure (Eq. 10-12), wetness
loss (Eq. 15), the middle control ellipse's rotation, elongation and relocation (Eq. 16-17),
splitting (Sec. 5.5, Eq. 18-19) and ink flow between primitives (Eq. 20).

Each function takes the ``HairyBrush`` and changes its fields (``brush_state`` has their
glossary); all m primitives and n key points at once. Gaps in the paper, filled as a real
brush behaves, are listed in ``brush``'s module doc and noted where they are implemented.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from ..core import exact
from ..core.exact import matmul
from ..core.frames import clip, cross, diff, norm, rotation_matrix, stack1, unit
from ..core.params import REF_RATE
from .bristles import HAIR_MM, contact_wetness, contact_wetness_one
from .bristles import draw as draw_bundles
from .state import CONTACT_EPS, key_point_fields, take_primitives

# Calibration scales: the paper's formulas are dimensionless in spirit; these map millimetres and
# seconds onto them so that every quality parameter in [0, 1] spans a useful range.
V_REF = 50.0  # mm/s, speed scale in Eq. 12 and 16
REC_RATE = 14.0  # 1/s, elastic recovery of free hair at e = 1
CAP_RATE = 12.0  # 1/s, ink drawn along a primitive's axis to drier key points (belly to tip)
MAX_FLATNESS = 5.0  # bound on a/b of the middle control ellipse
# bound on n / sum(wet) in Eq. 10 (a dry brush would give infinity): dry hair is as stressed as
# hair whose key points hold a third of a soaked one's liquid, and no more (issue 26). With the
# bound at 20, a brush running dry pressed ever harder (Eq. 12), so it lost its ink ever faster
# (Eq. 15) and dragged its hair ever further over the paper (Sec. 5.2.2): dry_ink's pressure
# rose to 0.8-1.1 where a loaded brush has 0.15, and its hair flew out of the character. A
# loaded brush, dipped again when it runs low, stays under 2.5 (the default writes the same).
WET_FACTOR_MAX = 3.0
SLIP = 0.3  # share of the way hair held on the paper slides after the brush each step
SPEND = 0.003  # per mm^2: the ink fresh paper takes from the hair that passes (lose_wetness)
SOAK = 0.003  # per mm^2 s: the ink the paper under the hair goes on taking (lose_wetness)
W_SQUEEZE = 0.3  # wetness below which Eq. 15's squeeze takes less of a key point's ink


def move(brush, pose6, vel6, dt: float):
    """Move the bottom control circle to the virtual position S^t and adjust the middle
    control axes (Sec. 5.2): the current active point (Eq. 13), deformation under the paper
    (Sec. 5.2.2), recovery (Eq. 14).

    Eq. 14's recovery raises the key points of the free hair; hair lying on the paper is held
    there by the hair pressing above it (and friction) and leaves the paper only when the
    lifted base pulls it off (``constrain``: the hair is inextensible). Raised with the rest,
    a lift of a hundredth of a millimetre freed all pressed hair at once, and it sprang back
    to its rest shape: every easing of the press in a stroke changed the mark's shape (the
    writer's IoU fell from 0.916 to 0.871 for a stress of at most 0.02)."""
    q = brush.q
    B0, R0 = brush.B, brush.R
    x, y, z, d, qq, rr = (float(v) for v in pose6)
    B1 = np.array([x, y, max(z, 0.0)])
    R1 = _rotation(d.hex(), qq.hex(), rr.hex())
    lift = B1[2] - B0[2]
    points = brush.cc
    contact = points[..., 2] <= CONTACT_EPS
    contact[:, 0] = False
    landing = ~contact.any(axis=1)  # no hair on the paper before this step (``constrain``)
    if brush.m == 1:  # one primitive: the same arithmetic on Python floats (fewer calls)
        new = _carry_one(brush, B1, R1, vel6, dt, lift)
        brush.B, brush.R = B1, R1
        active = _active_point_one(brush, new)
        if active is None:  # a key point to insert (Eq. 13): as for many primitives
            insert_active_point(brush, np.array([new]))
            constrain(brush, vel6, dt, landing)
            return
        fb = _fallback_direction(brush, vel6)
        drag = _landing_drag(fb, _speed(vel6) * dt, landing)
        drag0 = (0.0, 0.0) if drag is None else drag[0].tolist()
        sarc = brush.sarc[0].tolist()
        brush.cc = np.array([_constrain_one(new, sarc, fb[0].tolist(), drag0, first=True)])
        brush.active = np.array([active])
        return
    local = matmul(points - B0, R0)
    rest = np.zeros(local.shape)  # (local is float64: np.zeros_like without its wrapper)
    rest[..., 2] = -brush.sarc
    krec = min(1.0, q.e * REC_RATE * dt)  # elastic return of free hair (gap, see module doc)
    local = np.where(contact[..., None], local, local + krec * (rest - local))
    carried = B1 + matmul(local, R1.T)
    vxy = np.asarray(vel6[:2], dtype=float)
    speed = float(np.hypot(*vxy))
    lag = -vxy / speed if speed > 1e-9 else np.zeros(2)
    # Sec. 5.2.2: hair under the paper travels with the active point (held by friction, sliding
    # a little after the brush), plus dis = e * gamma (in units of r) along the drag
    dis = q.e * brush.gamma * brush.r * (dt * REF_RATE)
    held = points.copy()
    held[..., :2] += SLIP * (carried[..., :2] - points[..., :2]) + dis[:, None, None] * lag
    new = np.where(contact[..., None], held, carried)
    _follow(brush, B1, vxy, speed)
    if lift > 0:  # Eq. 14: cz += gamma * |dsz| * tr(dsz), on the hair not held by the paper
        new[:, 1:, 2] += np.where(contact[:, 1:], 0.0, brush.gamma[:, None] * lift)
    new[:, 0] = B1
    brush.B, brush.R = B1, R1
    insert_active_point(brush, new)
    constrain(brush, vel6, dt, landing)


def _carry_one(brush, B1, R1, vel6, dt: float, lift: float) -> list:
    """``move``'s key points of one primitive before the active point (a list of [x, y, z]),
    on Python floats: the same operations in the same order as the arrays' (a product with a
    rotation summed over its index 0, 1, 2, as ``exact.matmul``). Sets ``travel`` as ``move``
    does."""
    q = brush.q
    b0, b1, b2 = brush.B.tolist()
    (r00, r01, r02), (r10, r11, r12), (r20, r21, r22) = brush.R.tolist()
    c0, c1, c2 = B1.tolist()
    (s00, s01, s02), (s10, s11, s12), (s20, s21, s22) = R1.tolist()
    vxy = np.asarray(vel6[:2], dtype=float)
    speed = float(np.hypot(*vxy))
    lx, ly = (-vxy / speed).tolist() if speed > 1e-9 else (0.0, 0.0)
    _follow(brush, B1, vxy, speed)
    krec = min(1.0, q.e * REC_RATE * dt)  # elastic return of free hair (gap, see module doc)
    gamma = float(brush.gamma[0])
    dis = q.e * gamma * brush.r * (dt * REF_RATE)
    rise = gamma * lift if lift > 0 else None  # Eq. 14
    out = [[c0, c1, c2]]
    points, sarc = brush.cc[0].tolist(), brush.sarc[0].tolist()
    for j in range(1, len(points)):
        px, py, pz = points[j]
        dx, dy, dz = px - b0, py - b1, pz - b2
        ux = dx * r00 + dy * r10 + dz * r20
        uy = dx * r01 + dy * r11 + dz * r21
        uz = dx * r02 + dy * r12 + dz * r22
        on = pz <= CONTACT_EPS
        if not on:  # free hair springs back toward its rest shape (0, 0, -sarc)
            ux = ux + krec * (0.0 - ux)
            uy = uy + krec * (0.0 - uy)
            uz = uz + krec * (-sarc[j] - uz)
        cx = c0 + (ux * s00 + uy * s01 + uz * s02)
        cy = c1 + (ux * s10 + uy * s11 + uz * s12)
        cz = c2 + (ux * s20 + uy * s21 + uz * s22)
        if on:  # Sec. 5.2.2: held by the paper, sliding a little after the brush, and dragged
            cx = px + (SLIP * (cx - px) + dis * lx)
            cy = py + (SLIP * (cy - py) + dis * ly)
            cz = pz
        if rise is not None:
            cz += 0.0 if on else rise
        out.append([cx, cy, cz])
    return out


def _follow(brush, B1, vxy, speed: float):
    """The brush's direction of travel (``travel``, read where the hair is laid, Sec. 5.2.2's
    drag, and a split's children, Sec. 5.5) from the base's velocity ``vxy`` (speed its
    length) now at ``B1``. Added beyond the paper, which has no direction of travel: it turns
    only with motion longer than a hair's width (HAIR_MM). ``travel_from`` trails the base on
    a leash HAIR_MM long; the base sets ``travel`` only when it pulls the leash (moving on, or
    turning by up to a right angle, does at every step: the same directions as the velocity's).
    A creep back of less than twice HAIR_MM, the base nudged while it rests on the toe, leaves
    it: a resting toe does not lay its hair lines backwards across the flick's (issue 26)."""
    x, y = float(B1[0]), float(B1[1])
    ax, ay = brush.travel_from.tolist()  # held where the base was at the free state at first
    dx, dy = x - ax, y - ay
    gone = math.hypot(dx, dy)
    if gone <= HAIR_MM:  # within the leash: travel stays
        return
    # pulled: the leash's end follows at HAIR_MM behind the base
    brush.travel_from = np.array([x - HAIR_MM * dx / gone, y - HAIR_MM * dy / gone])
    if speed > 1.0:
        brush.travel = vxy / speed


def _active_point_one(brush, new: list):
    """``insert_active_point`` of one primitive where no key point is inserted, on Python
    floats (the same tests on the same numbers): the active point's index (-1: none), a key
    point snapped to it laid on the paper in ``new``; None where one would be inserted."""
    n = len(new)
    j = next((k for k in range(1, n) if new[k][2] <= CONTACT_EPS), None)
    if j is None:
        return -1
    x0, y0, z0 = new[j - 1]
    x1, y1, z1 = new[j]
    lam = _min(_max(z0 / _max(z0 - z1, 1e-12), 0.0), 1.0)  # clip
    dx, dy, dz = x1 - x0, y1 - y0, z1 - z0
    seg = math.sqrt(dx * dx + dy * dy + dz * dz)
    snap = 0.15 * brush.L / (n - 1)
    near_prev = lam * seg < snap
    if not near_prev and not (1.0 - lam) * seg < snap and z0 > CONTACT_EPS:
        return None
    active = j - 1 if near_prev and z0 > CONTACT_EPS else j
    new[active][2] = 0.0
    return active


@functools.lru_cache(maxsize=256)
def _rotation(d: str, q: str, r: str) -> np.ndarray:
    """rotation_matrix of the angles (their float.hex: -0.0 is not 0.0), read-only, kept: a
    brush held at one tilt through a stroke (as the writer holds it) turns by the same matrix
    step after step, built once (issue 28)."""
    R = rotation_matrix(float.fromhex(d), float.fromhex(q), float.fromhex(r))
    R.flags.writeable = False
    return R


def insert_active_point(brush, new):
    """Eq. 13: the axis's intersection with psi becomes a key point; its ink comes from its
    neighbours by distance-weighted linear interpolation. n stays constant (module doc)."""
    m, n = brush.m, brush.n
    z = new[..., 2]
    below = z <= CONTACT_EPS
    below[:, 0] = False
    has = below.any(axis=1)
    if not has.any():  # no key point on the paper: no active point (issue 28: at once)
        brush.cc = new
        brush.active = np.full(m, -1)
        return
    j = np.where(has, below.argmax(axis=1), n)  # first key point on/under the paper
    jj = clip(j, 1, n - 1)
    idx = np.arange(m)
    p0, p1 = new[idx, jj - 1], new[idx, jj]
    z0, z1 = p0[:, 2], p1[:, 2]
    lam = clip(z0 / np.maximum(z0 - z1, 1e-12), 0.0, 1.0)
    seg = norm(p1 - p0)
    snap = 0.15 * brush.L / (n - 1)
    near_prev = lam * seg < snap
    near_next = (1.0 - lam) * seg < snap
    insert = has & ~near_prev & ~near_next & (z0 > CONTACT_EPS)
    active = np.where(has, np.where(near_prev & (z0 > CONTACT_EPS), jj - 1, jj), -1)
    # snapping to an existing key point: it becomes the active point, on the paper
    snapped = has & ~insert
    new[idx[snapped], active[snapped], 2] = 0.0
    brush.cc = new
    if not insert.any():
        brush.active = active
        return
    point = p0 + lam[:, None] * (p1 - p0)
    point[:, 2] = 0.0
    # Eq. 13: x_j = (|cc_{j+1} - cc_j| x_{j-1} + |cc_j - cc_{j-1}| x_{j+1})
    #             / |cc_{j+1} - cc_{j-1}|
    w_prev, w_next = 1.0 - lam, lam
    pos = np.where(insert, jj, n)  # rows without insertion append a dummy, dropped again
    ar = np.arange(n + 1)
    src = np.where(ar[None, :] < pos[:, None], ar[None, :], ar[None, :] - 1)
    src = clip(src, 0, n - 1)

    def extend(field, value):
        if field.ndim == 2:
            out = np.take_along_axis(field, src, 1)
            out[idx, pos] = value
        else:
            out = np.take_along_axis(field, src[..., None], 1)
            out[idx, pos] = value
        return out

    def interp(field):
        a = field[idx, jj - 1]
        b = field[idx, jj]
        if field.ndim == 2:
            return w_prev * a + w_next * b
        return w_prev[:, None] * a + w_next[:, None] * b

    sarc = extend(brush.sarc, interp(brush.sarc))
    # drop the interior key point with the smallest arc gap (not first, last or active)
    gap = np.full((m, n + 1), np.inf)
    gap[:, 1:-1] = sarc[:, 2:] - sarc[:, :-2]
    gap[idx, pos] = np.inf
    drop = np.where(insert, gap.argmin(axis=1), n)
    keep = ar[None, :] != drop[:, None]

    def shrink(arr):
        return arr[keep].reshape((m, n) + arr.shape[2:])

    brush.sarc = shrink(sarc)
    brush.cc = shrink(extend(new, point))
    for name in key_point_fields(exclude=("sarc", "cc")):  # the ink, Eq. 13
        field = getattr(brush, name)
        setattr(brush, name, shrink(extend(field, interp(field))))
    brush.active = np.where(insert, np.where(drop < pos, pos - 1, pos), active)


def constrain(brush, vel6, dt: float = 0.0, landing=None):
    """Hair is inextensible and cannot pass through the paper. Walking from the bottom
    control circle to the tip: a key point too far from its predecessor is pulled after it
    (sliding on the paper); a key point on the paper lies flat at its full arc distance, the
    way the hair bends from its predecessor.

    Beyond the paper (issue 26.2), the hair that lands: a primitive none of whose hair lay on
    the paper before this step (``landing``, per primitive; None: none lands) lays its hair
    on it the way it bends plus the way the base drags it, back along the way the brush moves
    by the base's travel over the step (dt; along the tilt of a tilted brush, ``fb``): the
    tip touches and stays while the base goes on (``_landing_drag``). The bend alone of hair
    that has sprung back nearly straight in the air (hundredths of a millimetre left of the
    last stroke's flick) laid the landing tip any way at all, ahead of the motion or across
    it: a thread of hair out of the head (朋's inner 横, 柱's dot)."""
    points = brush.cc
    m, n = brush.m, brush.n
    fb = _fallback_direction(brush, vel6)
    drag = _landing_drag(fb, _speed(vel6) * dt, landing)  # (most steps: None)
    if m == 1:  # one primitive: the same arithmetic on Python floats (fewer calls)
        drag0 = (0.0, 0.0) if drag is None else drag[0].tolist()
        points[0, 1:] = _constrain_one(
            points[0].tolist(), brush.sarc[0].tolist(), fb[0].tolist(), drag0
        )
        return
    prev = points[:, 0]
    segs = brush.sarc[:, 1:] - brush.sarc[:, :-1]
    for j in range(1, n):
        p = points[:, j]
        d = p - prev
        dist = norm(d)
        seg = segs[:, j - 1]
        scale = np.minimum(1.0, seg / np.maximum(dist, 1e-12))
        cand = prev + d * scale[:, None]
        on_paper = (p[:, 2] <= CONTACT_EPS) | (cand[:, 2] <= CONTACT_EPS)
        h = np.maximum(prev[:, 2], 0.0)
        reach = on_paper & (seg > h)
        if reach.any():  # lies flat on the paper at its full arc distance
            H = np.sqrt(np.maximum(seg * seg - h * h, 0.0))
            dxy = d[:, :2] if drag is None else d[:, :2] + drag
            nd = norm(dxy)
            dirxy = np.where(nd[:, None] > 1e-9, dxy / np.maximum(nd, 1e-12)[:, None], fb)
            flat = np.zeros((m, 3))
            flat[:, :2] = prev[:, :2] + H[:, None] * dirxy
            p = np.where(reach[:, None], flat, cand)
        else:
            p = cand
        np.maximum(p[:, 2], 0.0, out=p[:, 2])
        points[:, j] = p
        prev = p


def _fallback_direction(brush, vel6) -> np.ndarray:
    """(m, 2): the way a key point on the paper lies from its predecessor where the hair gives
    none (``constrain``): the brush's lean, else the way back along its motion."""
    m = brush.m
    shaft = -brush.R[:, 2]
    vxy = np.asarray(vel6[:2], dtype=float)
    sp = _speed(vel6)
    if np.hypot(shaft[0], shaft[1]) > 0.05:
        return np.tile(shaft[:2] / np.hypot(shaft[0], shaft[1]), (m, 1))
    if sp > 1.0:
        return np.tile(-vxy / sp, (m, 1))
    # a vertical brush at rest lays its hair back along the way it came
    fb = np.tile(-brush.travel, (m, 1)) + 0.25 * brush.lay
    fb /= norm(fb, axis=1, keepdims=True)
    return fb


def _speed(vel6) -> float:
    """The brush's speed over the paper (mm/s) from its velocity ``vel6``."""
    vxy = np.asarray(vel6[:2], dtype=float)
    return float(np.hypot(*vxy))


def _landing_drag(fb, travel: float, landing) -> np.ndarray | None:
    """(m, 2): the drag (mm) ``constrain`` adds to the bend of the hair of the primitives that
    land this step (``landing``): ``travel`` back along ``fb`` (the fallback direction), none
    for the others; None when none lands or the base does not travel."""
    if landing is None or not travel > 0.0 or not bool(np.any(landing)):
        return None
    return np.where(np.asarray(landing)[:, None], travel * fb, 0.0)


def _constrain_one(points, sarc, fb, drag=(0.0, 0.0), first: bool = False) -> list:
    """``constrain``'s walk for one primitive, on Python floats: the same operations in the
    same order as the arrays' (a length as sqrt((x^2 + y^2) + z^2), numpy's order; the larger
    of two equal numbers the second, as np.maximum picks it: -0 and +0 keep their signs).
    Returns the key points 2..n (with ``first``, 1..n). ``drag``: ``_landing_drag``'s row."""
    px, py, pz = points[0]
    gx, gy = drag[0], drag[1]
    out = [points[0]] if first else []
    for j in range(1, len(points)):
        qx, qy, qz = points[j]
        dx, dy, dz = qx - px, qy - py, qz - pz
        dist = math.sqrt(dx * dx + dy * dy + dz * dz)
        seg = sarc[j] - sarc[j - 1]
        scale = _min(1.0, seg / _max(dist, 1e-12))
        cx, cy, cz = px + dx * scale, py + dy * scale, pz + dz * scale
        on_paper = (qz <= CONTACT_EPS) | (cz <= CONTACT_EPS)
        h = _max(pz, 0.0)
        if on_paper and seg > h:  # lies flat on the paper at its full arc distance
            H = math.sqrt(_max(seg * seg - h * h, 0.0))
            if gx or gy:  # landing (``_landing_drag``)
                dx, dy = dx + gx, dy + gy
            nd = math.sqrt(dx * dx + dy * dy)
            if nd > 1e-9:
                ux, uy = dx / _max(nd, 1e-12), dy / _max(nd, 1e-12)
            else:
                ux, uy = fb
            cx, cy, cz = px + H * ux, py + H * uy, 0.0
        px, py, pz = cx, cy, _max(cz, 0.0)
        out.append((px, py, pz))
    return out


def _max(a: float, b: float) -> float:
    """np.maximum of two floats: b where they are equal (its sign of zero), NaN if either is."""
    return a if (a > b or a != a) else b


def _min(a: float, b: float) -> float:
    """np.minimum of two floats: b where they are equal, NaN if either is."""
    return a if (a < b or a != a) else b


def update_stress(brush, section_area, section_height, speed, dt):
    """Inner stress (Eq. 10, 11) and pressure (Eq. 12) of every primitive.

    section_area: S_i, bounding-box area of the drawing mark (mm^2); section_height: hei_i,
    distance from the mark to the tip control line's midpoint (mm); speed: |Vel| (mm/s).
    Lengths are made dimensionless by the brush's own size (r, L) so that the quality
    parameters in [0, 1] keep their meaning for any brush."""
    q, r, L, n = brush.q, brush.r, brush.L, brush.n
    if brush.m == 1:  # one primitive: the same arithmetic on Python floats (fewer calls)
        stress = _stress_one(brush, float(section_area[0]), float(section_height[0]))
        brush.touching = section_area > 0
        brush.contact = np.asarray(section_area, dtype=float).copy()
        brush.stress = np.array([stress])
        brush.gamma = np.array([(speed / V_REF) * stress * q.sm * q.e])
        return brush.stress, brush.gamma
    wet_factor = np.minimum(n / np.maximum(brush.wet.sum(axis=1), 1e-9), WET_FACTOR_MAX)
    cone = (section_area / (np.pi * r * r)) * (section_height / L)  # (S*hei/3) / (pi r^2 L/3)
    # Eq. 11: his = hsd + hdd; 1/len is bounded by len >= r/2 (the tip starts as a point)
    hsd = (brush.a / brush.b) * (0.5 * r) / np.maximum(brush.tiplen, 0.5 * r)
    local = matmul(brush.cc - brush.B, brush.R)
    # mc = cc0_1 - cc_1 is zero in the brush frame: its origin is the circle's centre. The
    # displacement from the rest shape (0, 0, -sarc) is taken as local - rest, its negative:
    # the same squares, so the same lengths (issue 28: fewer numpy calls)
    off = local[:, 1:].copy()
    off[..., 2] += brush.sarc[:, 1:]
    disp = norm(off)
    seglen = norm(diff(local, axis=1))
    hdd = (disp * seglen).sum(axis=1) / np.maximum(seglen.sum(axis=1), 1e-12) / L
    his = hsd + hdd
    area = (np.pi * brush.a * brush.b / 4.0) / (np.pi * r * r)
    brush.touching = section_area > 0
    brush.contact = np.asarray(section_area, dtype=float).copy()  # S_i, for Eq. 15's spending
    brush.stress = (1.0 - q.e) * wet_factor * cone * his * area  # Eq. 10
    brush.gamma = (speed / V_REF) * brush.stress * q.sm * q.e  # Eq. 12
    return brush.stress, brush.gamma


def _stress_one(brush, S: float, hei: float) -> float:
    """``update_stress``'s Eq. 10-11 for one primitive on Python floats: the same operations
    in the same order as the arrays' (a product with R summed over its index 0, 1, 2, as
    ``exact.matmul``; a length as sqrt((x^2 + y^2) + z^2); the sums over the key points by
    np.add.reduce, numpy's own order)."""
    q, r, L, n = brush.q, brush.r, brush.L, brush.n
    wet_factor = _min(n / _max(float(np.add.reduce(brush.wet[0])), 1e-9), WET_FACTOR_MAX)
    cone = (S / (np.pi * r * r)) * (hei / L)  # (S*hei/3) / (pi r^2 L/3)
    a, b, tip = float(brush.a[0]), float(brush.b[0]), float(brush.tiplen[0])
    hsd = _div(a, b) * (0.5 * r) / _max(tip, 0.5 * r)  # Eq. 11
    b0, b1, b2 = brush.B.tolist()
    (r00, r01, r02), (r10, r11, r12), (r20, r21, r22) = brush.R.tolist()
    disp, seglen, prev = [], [], None
    for (px, py, pz), s in zip(brush.cc[0].tolist(), brush.sarc[0].tolist(), strict=True):
        dx, dy, dz = px - b0, py - b1, pz - b2
        lx = dx * r00 + dy * r10 + dz * r20
        ly = dx * r01 + dy * r11 + dz * r21
        lz = dx * r02 + dy * r12 + dz * r22
        if prev is not None:  # the displacement from the rest shape, and the segment's length
            oz = lz + s
            disp.append(math.sqrt(lx * lx + ly * ly + oz * oz))
            sx, sy, sz = lx - prev[0], ly - prev[1], lz - prev[2]
            seglen.append(math.sqrt(sx * sx + sy * sy + sz * sz))
        prev = (lx, ly, lz)
    weighted = float(np.add.reduce(np.array([d * g for d, g in zip(disp, seglen, strict=True)])))
    hdd = weighted / _max(float(np.add.reduce(np.array(seglen))), 1e-12) / L
    area = (np.pi * a * b / 4.0) / (np.pi * r * r)
    return (1.0 - q.e) * wet_factor * cone * (hsd + hdd) * area  # Eq. 10


def lose_wetness(brush, dt):
    """Eq. 15: wet_{j+-s} -= ab * gamma / 2^(s+d), d = 1 for s = 0 and 2 otherwise. A
    primitive whose section touches the paper without a key point on it loses from its
    lowest key point.

    Model addition: the brush also loses the ink the paper takes, which Eq. 15's pressure term
    alone leaves almost whole (gamma is about 0.01 in regular script: a stroke spent a tenth
    of the load, and every stroke was as black as the first). The paper takes ink in
    proportion to its absorbency ab and the wetness of the hair on it: most where the hair
    meets fresh paper (``sweep``, the area it passes over a second: its width across the
    motion times its speed), and a little more for as long as it lies on the wet paper it has
    covered (S_i, ``contact``, Eq. 10): (SPEND sweep + SOAK S_i) ab wet dt, taken from the key
    points lying on the paper (the lowest one where none does), each in proportion to its
    wetness. Writing on, the brush runs from dark and wet after a dip to grey and dry over a
    few hundred millimetres of stroke; a pause spends a little more (the pool under the hair,
    ``bristles.lay``).

    Model change (issue 26): Eq. 15 takes the same wetness a step whatever the key point holds,
    so a brush dipped in little ink (dry_ink) was wrung out in a few centimetres and went on
    losing at that rate to the last drop. Pressure squeezes out the liquid between the hairs,
    not the film that capillarity holds on them: below W_SQUEEZE a key point gives up to
    Eq. 15 in proportion to what it holds, and the paper's own take (above) spends the rest, a
    share at a time, so a dry brush's streaks thin out along the stroke instead of stopping."""
    touching = brush.touching
    if not touching.any():
        return
    act = np.where(brush.active >= 0, brush.active, brush.cc[..., 2].argmin(axis=1))
    if brush.m == 1:  # one primitive: the same arithmetic on Python floats (fewer calls)
        shares = _squeeze_shares(brush.n)[act[0]].tolist()
        brush.wet[0] = _lose_one(brush, shares, dt)  # in place, as below
        return
    loss = brush.q.ab * brush.gamma[:, None] / _squeeze_shares(brush.n)[act] * (dt * REF_RATE)
    loss = loss * np.minimum(brush.wet / W_SQUEEZE, 1.0)  # the last ink stays (doc)
    on, wet_on = contact_wetness(brush)
    held = np.where(on, brush.wet, 0.0)
    total = held.sum(axis=1)
    spend = (SPEND * brush.sweep + SOAK * brush.contact) * brush.q.ab * wet_on * dt
    loss = loss + spend[:, None] * held / np.maximum(total, 1e-12)[:, None]
    if not touching.all():  # (a no-op where every primitive is on the paper: skipped)
        loss = np.where(touching[:, None], loss, 0.0)
    np.maximum(brush.wet - loss, 0.0, out=brush.wet)


def _lose_one(brush, shares: list, dt: float) -> list:
    """``lose_wetness`` of one primitive on the paper on Python floats, ``shares`` the active
    point's row of Eq. 15's table: the same operations in the same order as the arrays' (the
    sum over the key points by np.add.reduce, numpy's own order)."""
    ab, gamma = brush.q.ab, float(brush.gamma[0])
    wet = brush.wet[0].tolist()
    per = dt * REF_RATE
    loss = [
        ab * gamma / sh * per * _min(w / W_SQUEEZE, 1.0) for sh, w in zip(shares, wet, strict=True)
    ]
    on, wet_on = contact_wetness_one(brush)
    held = [w if o else 0.0 for o, w in zip(on, wet, strict=True)]
    total = _max(float(np.add.reduce(np.array(held))), 1e-12)
    sweep, contact = float(brush.sweep[0]), float(brush.contact[0])
    spend = (SPEND * sweep + SOAK * contact) * ab * wet_on * dt
    return [_max(w - (x + spend * h / total), 0.0) for w, x, h in zip(wet, loss, held, strict=True)]


@functools.cache
def _squeeze_shares(n: int) -> np.ndarray:
    """Eq. 15's 2^(s+d) of every key point j (columns) from every active point (rows), s =
    |j - active|, d = 1 for s = 0 and 2 otherwise: a table, so that a step takes a row of it
    instead of computing it (issue 28). Read-only."""
    j = np.arange(n)
    s = np.abs(j[None, :] - j[:, None])
    d = np.where(s == 0, 1, 2)
    table = exact.exp2(s + d)
    table.flags.writeable = False
    return table


def adjust_ellipse(brush, vel6, dt):
    """Eq. 16 (rotation and elongation of the middle control ellipse at constant hair area),
    Sec. 5.4 (the tip control line follows), Eq. 17 (relocation)."""
    q = brush.q
    vel = matmul(np.asarray(vel6[:3], dtype=float), brush.R) / V_REF  # brush frame, scaled
    touching = brush.touching
    if brush.m == 1:  # one primitive: the same arithmetic on Python floats (fewer calls)
        _adjust_ellipse_one(brush, vel.tolist(), dt, bool(touching[0]))
        if not touching[0]:
            brush.loc = clip(brush.loc, 0.05, 0.9)
            return
        _relocate(brush, True)
        return
    eo = brush.eori
    per = dt * REF_RATE
    rot = q.re * brush.gamma * matmul(eo, vel) * per  # Eq. 16
    inc = q.ie * brush.gamma * norm(cross(eo, vel)) * per  # Eq. 16
    # (every primitive on the paper, as in most of a stroke: the picks below are no-ops and
    # skipped; issue 28)
    every = touching.all()
    if not every:
        rot = np.where(touching, rot, 0.0)
        inc = np.where(touching, inc, 0.0)
    # rotate the minor axis about the shaft
    s, c = exact.sin_cos(rot)
    ex, ey = eo[:, 0] * c - eo[:, 1] * s, eo[:, 0] * s + eo[:, 1] * c
    brush.eori = unit(stack1([ex, ey, eo[:, 2]]))
    area = brush.a * brush.b
    a = brush.a + inc * brush.r
    a = np.minimum(a, np.sqrt(area * MAX_FLATNESS))
    # free state: the belly rounds and the tip closes again (gap: elastic return)
    krec = min(1.0, q.e * REC_RATE * dt)
    if not every:
        rnd = np.sqrt(area)
        a = np.where(touching, a, a + krec * (rnd - a))
    brush.a = a
    brush.b = area / a  # pi a b / 4 constant (Sec. 5.3)
    tl = brush.tiplen + inc * brush.r  # Sec. 5.4: the tip control line lengthens by inc
    on = np.minimum(tl, 0.5 * brush.a)
    brush.tiplen = on if every else np.where(touching, on, tl * (1.0 - krec))
    if not touching.any():  # no primitive on the paper moves its ellipse (issue 28: skipped)
        brush.loc = clip(brush.loc, 0.05, 0.9)
        return
    _relocate(brush, every)


def _relocate(brush, every: bool):
    """Eq. 17: loc' = nu loc + (1 - nu) (1/n) sum_j arc(P_1..P_{j+1}) / arc(P_1..P_n), for the
    primitives on the paper (``every``: all of them)."""
    q, touching = brush.q, brush.touching
    seg = norm(diff(brush.cc, axis=1))
    cum = seg.cumsum(axis=1)
    ideal = np.add.reduce(cum / np.maximum(cum[:, -1:], 1e-12), axis=1) / brush.n  # np.sum
    new_loc = q.nu * brush.loc + (1.0 - q.nu) * ideal
    brush.loc = clip(new_loc if every else np.where(touching, new_loc, brush.loc), 0.05, 0.9)


def _adjust_ellipse_one(brush, vel: list, dt: float, touching: bool):
    """``adjust_ellipse``'s Eq. 16 and Sec. 5.4 for one primitive on Python floats, ``vel``
    in the brush frame (scaled): the same operations in the same order as the arrays' (a dot
    product summed x, y, z; a length as sqrt((x^2 + y^2) + z^2); the picks of np.minimum and
    np.maximum, ``_min`` and ``_max``)."""
    q = brush.q
    e0, e1, e2 = brush.eori[0].tolist()
    v0, v1, v2 = vel
    gamma, r = float(brush.gamma[0]), brush.r
    per = dt * REF_RATE
    rot = q.re * gamma * (e0 * v0 + e1 * v1 + e2 * v2) * per  # Eq. 16
    c0, c1, c2 = e1 * v2 - e2 * v1, e2 * v0 - e0 * v2, e0 * v1 - e1 * v0  # eori x vel
    inc = q.ie * gamma * math.sqrt(c0 * c0 + c1 * c1 + c2 * c2) * per  # Eq. 16
    if not touching:
        rot, inc = 0.0, 0.0
    s, c = exact.sin_cos(rot)
    ex, ey = e0 * c - e1 * s, e0 * s + e1 * c
    length = _max(math.sqrt(ex * ex + ey * ey + e2 * e2), 1e-12)
    brush.eori = np.array([[ex / length, ey / length, e2 / length]])
    a0, b0, tip = float(brush.a[0]), float(brush.b[0]), float(brush.tiplen[0])
    area = a0 * b0
    a = _min(a0 + inc * r, _sqrt(area * MAX_FLATNESS))
    krec = min(1.0, q.e * REC_RATE * dt)
    if not touching:
        a = a + krec * (_sqrt(area) - a)
    tl = tip + inc * r  # Sec. 5.4: the tip control line lengthens by inc
    brush.a = np.array([a])
    brush.b = np.array([_div(area, a)])  # pi a b / 4 constant (Sec. 5.3)
    brush.tiplen = np.array([_min(tl, 0.5 * a) if touching else tl * (1.0 - krec)])


def _div(x: float, y: float) -> float:
    """x / y of floats as numpy divides them: inf or NaN (and numpy's warning) where y is 0
    (Python raises)."""
    return x / y if y != 0.0 else float(np.divide(np.float64(x), y))


def _sqrt(x: float) -> float:
    """np.sqrt of a float: NaN below zero (math.sqrt raises)."""
    return math.sqrt(x) if x >= 0.0 else math.nan


def split(brush):
    """Sec. 5.5: a primitive whose inner stress exceeds tre splits into k = floor(str/tre)
    primitives (Eq. 18), each with 1/k of the hair: a, b / sqrt(k) and len / k (Eq. 19).
    Key points move by rand * (str - tre) (in units of r), growing from zero at the shared
    bottom control circle to full at the tip (hair fans out from the ferrule).

    Beyond the paper (issue 26), where the children go: the paper's rand is a random direction,
    and nothing keeps a child inside the hair it came from; a soft brush (goat_soft, stress
    several times tre) split step after step, every child thrown a random way by up to
    (str - tre) r again, and clusters of hair left the stroke as blobs and broken pieces. A
    real brush parts into clumps side by side across the stroke, within the width the hair
    had, each drawing its own streak along it: here the k children lie side by side across
    the way the brush travels, each at its share of the width with a random jitter (the
    paper's rand) of half a share, moved by (str - tre) r at most and never further than a
    child of width w / sqrt(k) can go inside its parent's width w across the way
    (``_split_offsets``). A child splitting again stays inside its own width, so the hair of a
    split brush never spreads wider than the belly it was."""
    tre = max(brush.q.tre, 1e-3)
    over = brush.stress / tre
    # no primitive on the paper with floor(str / tre) >= 2 (as in most steps): no split, at
    # once (issue 28; NaN splits nothing either way, an infinite quotient goes on below)
    room = brush.max_primitives - brush.m
    if room <= 0 or not ((over >= 2.0) & brush.touching).any():
        return 0
    k = np.floor(over).astype(int)
    k = np.where(brush.touching, k, 1)
    k = np.clip(k, 1, None)
    if room <= 0 or not np.any(k >= 2):
        return 0
    extra = k - 1
    # cap the total, taking from the most stressed first (deterministic order)
    order = np.argsort(-brush.stress, kind="stable")
    budget = room
    for i in order:
        share = min(extra[i], budget)
        extra[i] = share
        budget -= share
    k = extra + 1
    if not np.any(k >= 2):
        return 0
    reps = k
    src = np.repeat(np.arange(brush.m), reps)
    kk = np.repeat(k, reps).astype(float)
    total = len(src)
    split_child = kk > 1
    across = _split_offsets(brush, src, kk, tre)
    frac = brush.sarc[src] / brush.L
    offset = across[:, None, :] * frac[..., None]
    offset = np.where(split_child[:, None, None], offset, 0.0)
    take_primitives(brush, src)  # every field copied to the children, then what differs:
    brush.cc = brush.cc + offset
    brush.cc[..., 2] = np.maximum(brush.cc[..., 2], 0.0)
    brush.cc[:, 0] = brush.B
    sq = np.sqrt(kk)
    brush.a = brush.a / sq  # Eq. 19
    brush.b = brush.b / sq
    brush.tiplen = brush.tiplen / kk
    for name, value in draw_bundles(brush.rng, total).items():  # the children's own bundles
        setattr(brush, name, np.where(split_child[:, None], value, getattr(brush, name)))
    ang = brush.rng.random(total) * 2 * np.pi
    brush.lay = np.stack(exact.sin_cos(ang)[::-1], axis=1)
    new = int(np.sum(k - 1))
    brush.splits += new
    return new


def _split_offsets(brush, src, kk, tre) -> np.ndarray:
    """Where each child of a split goes at the tip (``split``): (total, 3) mm in the paper's
    frame, across the way the brush travels (``travel``), the children of one parent side by
    side in order over the parent's width across it (its middle control ellipse, Eq. 6, seen
    across the way), the outermost a child's half width inside its edges (and no further than
    the paper's (str - tre) r), each jittered by half a share by the seeded generator."""
    total = len(src)
    first = np.r_[0, np.flatnonzero(np.diff(src)) + 1]  # each parent's first child
    order = np.arange(total) - np.repeat(first, np.diff(np.r_[first, total]))
    jitter = brush.rng.random(total) - 0.5
    spread = np.maximum(0.5 - 0.5 / kk, 1e-12)  # the outermost child's place (none unsplit)
    place = clip(((order + 0.5 + 0.5 * jitter) / kk - 0.5) / spread, -1.0, 1.0)
    across = np.array([-brush.travel[1], brush.travel[0], 0.0])  # left of the way it goes
    eo = matmul(brush.eori[src], brush.R.T)  # the minor axis, paper frame
    major = cross(np.broadcast_to(brush.R[:, 2], eo.shape), eo)
    width = np.hypot(brush.a[src] * matmul(major, across), brush.b[src] * matmul(eo, across))
    room = 0.5 * width * (1.0 - 1.0 / np.sqrt(kk))  # a child of width / sqrt(k) inside
    reach = np.minimum(np.maximum(brush.stress[src] - tre, 0.0) * brush.r, room)
    return across[None, :] * (place * reach)[:, None]


def ink_flow(brush):
    """Eq. 20: each key point's wetness moves toward the mean wetness of the other
    primitives' key points within the diffusion distance eta (in units of the brush's
    diameter), by the share pw."""
    if brush.m < 2 or brush.q.pw <= 0.0:
        return
    eta = brush.q.eta * 2.0 * brush.r
    pts = brush.cc.reshape(-1, 3)
    wet = brush.wet.reshape(-1)
    owner = np.repeat(np.arange(brush.m), brush.n)
    # |P_i - P_j|^2 a coordinate at a time (the same sums as over the last axis, faster)
    dx = pts[:, None, 0] - pts[None, :, 0]
    d2 = dx * dx
    for k in (1, 2):
        dk = pts[:, None, k] - pts[None, :, k]
        d2 += dk * dk
    near = (d2 <= eta * eta) & (owner[:, None] != owner[None, :])  # tr(eta - |..|), j != i
    cnt = near.sum(axis=1)
    # summed without BLAS: its threaded matrix-vector product would keep a second core
    # spinning every step (and its kernels differ between machines)
    mean = np.where(cnt > 0, np.einsum("ij,j->i", near, wet) / np.maximum(cnt, 1), wet)
    brush.wet = (wet * (1.0 - brush.q.pw) + mean * brush.q.pw).reshape(brush.m, brush.n)


def capillary(brush, dt):
    """Ink wicks along the axis toward drier key points (gap fill, see module doc)."""
    k = min(0.5, CAP_RATE * dt)
    w = brush.wet
    flux = k * 0.5 * (w[:, 2:] - w[:, 1:-1])  # between key points 2..n (not the ferrule)
    if flux.size == 0:
        return
    w[:, 1:-1] += flux
    w[:, 2:] -= flux
