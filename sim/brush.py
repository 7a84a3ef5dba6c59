# SPDX-License-Identifier: GPL-3.0-or-later
"""The virtual hairy brush HB = (CWP, Qp) (Eq. 1): writing primitives (Sec. 3.2), the brush
states (Sec. 3.3-3.6) and the dynamic adjustments (Sec. 5).

All m writing primitives share one set of arrays: key points are ``(m, n, ...)`` (every primitive
has the same number n of key points, as the paper's split keeps it, Sec. 5.5), so every step is
vectorised over primitives and key points.

Coordinates are millimetres in the paper's frame: x to the right, y up the sheet, z up from the
paper plane psi (z = 0). The brush's local frame (Fig. 2(c)) has the bottom control circle as
its x-y plane, its centre as the origin and the shaft as +z; the free hair hangs along -z.
Its orientation is R = Rx(q) Ry(d) Rz(r): r turns the brush about its handle, d deflects it
sideways (about the paper's y axis), q forward (about the x axis).

Gaps in the paper, filled as a real brush behaves (each also noted where it is implemented):
- Key points are material points of the hair, each with its arc coordinate ``sarc`` along the
  hair; the hair is inextensible. Key points never pass through the paper; a key point pressed
  onto the paper lies flat on it at its full arc distance from the previous one (the brush's
  belly spreads on the paper), and is held there by friction until the hair drags it on.
- Eq. 14 only lifts the key points. Free hair also springs back toward its straight rest shape
  at a rate proportional to the elasticity e (Sec. 7.1: "if the brush recovers too quickly,
  decrease e"), and the middle control ellipse and tip control line relax toward round/point.
- The number of key points stays n: inserting the active point (Eq. 13) drops the interior key
  point that carries least shape (the smallest arc gap), which answers the paper's own remark
  (Sec. 9) that key points otherwise keep increasing.
- Ink wicks along each primitive's axis toward drier key points (capillarity), so that the belly
  feeds the tip as in a real brush; dipping again re-gathers split hair into one primitive and
  restores the point (Sec. 9, "hair merging", "multiple dipping").
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .nurbs import (
    SweepLayout,
    bezier_form,
    bspline_bases,
    derivative_ctrl,
    interpolate_cubic,
    rotation_minimising_frames,
    surface_control_net,
)
from .params import BrushGeometry, InkSpec, QualityParams

# Calibration scales: the paper's formulas are dimensionless in spirit; these map millimetres and
# seconds onto them so that every quality parameter in [0, 1] spans a useful range.
V_REF = 50.0  # mm/s, speed scale in Eq. 12 and 16
REC_RATE = 14.0  # 1/s, elastic recovery of free hair at e = 1
CAP_RATE = 3.0  # 1/s, capillary flow of ink along a primitive's axis
MAX_PRIMITIVES = 32
MAX_FLATNESS = 5.0  # bound on a/b of the middle control ellipse
WET_FACTOR_MAX = 20.0  # bound on n / sum(wet) in Eq. 10 (a dry brush would give infinity)
HAIR_BINS = 48  # hair bundles across a primitive for the dry-brush draw (Eq. 27)
STREAK_REDRAW = 0.03  # share of hair bundles whose dryness is redrawn each step
CONTACT_EPS = 1e-6  # mm: a key point this close to psi is on the paper
# The paper's per-time-slice updates (Sec. 5.2.2, Eq. 15, 16) are applied at this reference rate
# and scaled by dt * REF_RATE otherwise, so a gesture leaves the same artwork at any sample rate.
REF_RATE = 30.0  # time slices per second
SLIP = 0.3  # share of the way hair held on the paper slides after the brush each step


# ink information carried by a key point (Eq. 3-5), as columns of one array
INK_FIELDS = {
    "wet": slice(0, 1),
    "col": slice(1, 4),
    "wr": slice(4, 5),
    "cr": slice(5, 6),
    "wv": slice(6, 9),
    "cv": slice(9, 12),
}
INK_WIDTH = 12


def ink_field(rows, name: str) -> np.ndarray:
    """One field of a stacked ink array (..., INK_WIDTH); scalars lose their last axis."""
    out = rows[..., INK_FIELDS[name]]
    return out[..., 0] if out.shape[-1] == 1 else out


def rotation_matrix(d_deg: float, q_deg: float, r_deg: float) -> np.ndarray:
    """R = Rx(q) Ry(d) Rz(r), angles in degrees (Sec. 4, Fig. 6(a))."""
    d, q, r = np.radians([d_deg, q_deg, r_deg])
    cx, sx = np.cos(q), np.sin(q)
    cy, sy = np.cos(d), np.sin(d)
    cz, sz = np.cos(r), np.sin(r)
    rx = np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    ry = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    rz = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    return rx @ ry @ rz


def angles_from_matrix(R) -> tuple[float, float, float]:
    """(d, q, r) in degrees with rotation_matrix(d, q, r) == R, for |d| < 90 (inverse of the
    above; Blender's Euler mode 'ZYX' with (x, y, z) = (q, d, r) is the same matrix)."""
    R = np.asarray(R, dtype=float)
    d = np.arcsin(np.clip(R[0, 2], -1.0, 1.0))
    q = np.arctan2(-R[1, 2], R[2, 2])
    r = np.arctan2(-R[0, 1], R[0, 0])
    return tuple(float(v) for v in np.degrees([d, q, r]))


_add = np.add.reduce  # np.sum without its Python wrapper (the same sums)


def _norm(v, axis=-1, keepdims=False):
    return np.sqrt(_add(v * v, axis=axis, keepdims=keepdims))


def _cross(a, b):
    """np.cross of (..., 3) vectors without its Python wrapper (the same products)."""
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    out[..., 0] = a1 * b2 - a2 * b1
    out[..., 1] = a2 * b0 - a0 * b2
    out[..., 2] = a0 * b1 - a1 * b0
    return out


def _unit(v, fallback=None):
    n = _norm(v, keepdims=True)
    out = v / np.maximum(n, 1e-12)
    if fallback is not None:
        out = np.where(n > 1e-9, out, fallback)
    return out


@dataclass
class Sections:
    """The swept solid of every primitive: station sections and the surface's grid rows."""

    centres: np.ndarray  # (m, Ms, 3) station centres on the middle control axis
    U: np.ndarray  # (m, Ms, 3) semi-major axis vectors
    V: np.ndarray  # (m, Ms, 3) semi-minor axis vectors
    T: np.ndarray  # (m, Ms, 3) unit tangents
    params: np.ndarray  # (m, n) axis parameters of the key points
    rows_c: np.ndarray  # (m, Ns, 3) grid row centres (axis points V^)
    rows_U: np.ndarray
    rows_V: np.ndarray
    rows_T: np.ndarray


class HairyBrush:
    """The brush: collection of writing primitives WP_i = (C_i, E_i, L_i, A_i) plus Qp."""

    def __init__(
        self,
        geometry: BrushGeometry,
        quality: QualityParams,
        rng: np.random.Generator,
        layout: SweepLayout | None = None,
    ):
        self.geometry = geometry
        self.q = quality
        self.rng = rng
        self.layout = layout or SweepLayout()
        self.r = float(geometry.base_radius_mm)  # bottom control circle radius (Eq. 2)
        self.L = float(geometry.hair_length_mm)
        self.n = int(geometry.key_points)
        self.B = np.array([0.0, 0.0, self.L + 10.0])  # cen: centre of the bottom control circle
        self.R = np.eye(3)
        self.state = "initial"  # Sec. 3.3: initial -> dipping -> working
        self.travel = np.array([1.0, 0.0])  # last horizontal direction of motion
        self.splits = 0
        self.max_primitives = MAX_PRIMITIVES
        self._free_state(1)

    # ----------------------------------------------------------------- states (Sec. 3.3-3.5)
    def _free_state(self, m: int, a=None, b=None):
        """Sec. 3.4: axis a straight line, ellipse a circle, tip line a point."""
        n, L, g = self.n, self.L, self.geometry
        self.sarc = np.tile(np.linspace(0.0, L, n), (m, 1))
        self.cc = self._rest_world(self.sarc, self.B, self.R)
        self.col = np.zeros((m, n, 3))
        self.wet = np.zeros((m, n))
        self.wv = np.zeros((m, n, 3))
        self.cv = np.zeros((m, n, 3))
        self.wr = np.zeros((m, n))
        self.cr = np.zeros((m, n))
        d = g.belly_diameter_mm
        self.a = np.full(m, d if a is None else a)
        self.b = np.full(m, d if b is None else b)
        self.loc = np.full(m, g.belly_loc)
        self.eori = np.tile([0.0, 1.0, 0.0], (m, 1))  # minor axis orientation, brush frame
        self.tiplen = np.zeros(m)
        self.gamma = np.zeros(m)
        self.stress = np.zeros(m)
        self.hair_u = self.rng.random((m, HAIR_BINS))
        ang = self.rng.random(m) * 2 * np.pi
        self.lay = np.stack([np.cos(ang), np.sin(ang)], axis=1)
        self.active = np.full(m, -1)
        self.touching = np.zeros(m, dtype=bool)

    @property
    def m(self) -> int:
        return self.cc.shape[0]

    @staticmethod
    def _rest_world(sarc, B, R):
        local = np.zeros(sarc.shape + (3,))
        local[..., 2] = -sarc
        return B + local @ R.T

    def hair_area(self) -> float:
        """Number of hair threads, approximated by sum_i pi a_i b_i / 4 (Sec. 5.3, 5.5)."""
        return float(np.sum(np.pi * self.a * self.b / 4.0))

    def place(self, pose6):
        """Put the brush somewhere in its free state shape (no dynamics)."""
        x, y, z, d, q, r = (float(v) for v in pose6)
        self.B = np.array([x, y, max(z, 0.0)])
        self.R = rotation_matrix(d, q, r)
        self.cc = self._rest_world(self.sarc, self.B, self.R)
        np.maximum(self.cc[..., 2], 0.0, out=self.cc[..., 2])

    def dip(self, ink: InkSpec, depth: float | None = None, color=None, wetness=None):
        """Dipping state (Sec. 3.5, Eq. 7-8). The key points within ``depth`` (a fraction of the
        hair length, from the tip) are soaked; the others interpolate linearly toward the dry,
        paper-coloured first key point. Dipping also re-gathers split hair into one primitive and
        restores the point (paper's future work: merging, multiple and partial dipping): the old
        load is kept where it is wetter than the new one."""
        depth = ink.depth if depth is None else float(depth)
        rgb = np.asarray(ink.color if color is None else color, dtype=float)
        wetness = ink.wetness if wetness is None else float(wetness)
        old_wet = self.wet.mean(axis=0)
        old_col = self.col.mean(axis=0)
        self._free_state(1, a=np.sqrt(4.0 * self.hair_area() / np.pi))
        self.place(np.r_[self.B, 0.0, 0.0, 0.0])
        # ink colour as density: 0 is the paper's colour (Eq. 7 "col_P1 = 0 is pure white")
        ink_col = 1.0 - np.clip(rgb, 0.0, 1.0)
        s = self.sarc[0]
        soaked = s >= (1.0 - depth) * self.L - 1e-9
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
        self.col[0] = np.where(keep_old[:, None], mix_col, new_col)
        self.wet[0] = np.where(keep_old, old_wet, new_wet)
        self.wr[0] = ink.wr
        self.cr[0] = ink.cr
        self.wv[0] = ink.wv
        self.cv[0] = ink.cv
        self.state = "dipping"

    # ---------------------------------------------------------------------------- geometry
    def sections(self) -> Sections:
        """Sweep the bottom control circle, middle control ellipse and tip control line along
        the middle control axis (Sec. 2, 3.2) with rotation-minimising frames."""
        lay = self.layout
        ctrl, knots, params = interpolate_cubic(self.cc)  # A_i through P_i,1..n (Sec. 3.2.3)
        u = lay.station_u
        bases = bspline_bases(knots, 3, np.broadcast_to(u, (self.m, len(u))))
        centres = bases[3] @ ctrl
        dq, _ = derivative_ctrl(ctrl, knots, 3)
        T = _unit(bases[2][..., 1:-1] @ dq)  # the derivative's basis is degree 2 on knots[1:-1]
        # initial frame: the bottom control circle's own x axis (cori = shaft direction)
        x0 = self.R[:, 0]
        r0 = x0 - np.einsum("ij,j->i", T[:, 0], x0)[:, None] * T[:, 0]
        r0 = _unit(r0, fallback=self.R[:, 1])
        N = rotation_minimising_frames(centres, T, r0)
        Bn = _cross(T, N)
        # orientation of the middle control ellipse (Eq. 6): its minor axis eori, projected
        # into the normal plane at loc, fixes the profiles' angle within the swept frames
        ks = np.clip(np.searchsorted(u, self.loc), 0, len(u) - 1)
        idx = np.arange(self.m)
        Nl, Bl = N[idx, ks], Bn[idx, ks]
        eo = self.eori @ self.R.T
        cv = np.einsum("ij,ij->i", eo, Nl)
        sv = np.einsum("ij,ij->i", eo, Bl)
        h = np.hypot(cv, sv)
        cv = np.where(h > 1e-9, cv / np.maximum(h, 1e-12), 0.0)
        sv = np.where(h > 1e-9, sv / np.maximum(h, 1e-12), 1.0)
        vhat = cv[:, None, None] * N + sv[:, None, None] * Bn  # minor axis direction
        uhat = sv[:, None, None] * N - cv[:, None, None] * Bn  # major axis direction
        alpha, beta = self.profile_semiaxes(u)
        U = alpha[..., None] * uhat
        V = beta[..., None] * vhat
        rows = lay.row_from_station
        rows_T = _unit(np.einsum("ij,mjk->mik", rows, T))
        return Sections(
            centres,
            U,
            V,
            T,
            params,
            np.einsum("ij,mjk->mik", rows, centres),
            np.einsum("ij,mjk->mik", rows, U),
            np.einsum("ij,mjk->mik", rows, V),
            rows_T,
        )

    def surface_nets(self, sec: Sections | None = None):
        """Every primitive's sweep surface SS(s, t) (Sec. 2, 6) as a homogeneous NURBS control
        net in paper millimetres, refined to Bezier form along s so that a Blender NURBS surface
        (which has no free knot vector) holds exactly the same geometry. Returns (nets
        (m, 3 * spans + 1, 9, 4), breakpoints along s); around the axis the net is the 9-point
        rational circle (CIRCLE_KNOTS, already Bezier form)."""
        sec = self.sections() if sec is None else sec
        net = surface_control_net(self.layout, sec.centres, sec.U, sec.V)  # (m, Ms, 9, 4)
        refined, breaks = bezier_form(np.moveaxis(net, 1, 0), self.layout.knots_s, 3)
        return np.moveaxis(refined, 0, 1), breaks

    def profile_semiaxes(self, u):
        """Semi-axes of the sweep profiles at axis parameters u: the bottom control circle
        (radius r) at u = 0, the middle control ellipse (a/2, b/2) at u = loc, the tip control
        line (len/2, 0) at u = 1. Between them the brush bulges to its belly (sine) and tapers
        to an ogive tip (1 - x^2), the shape of a real brush head (Fig. 2(a), 5(a))."""
        u = np.asarray(u)[None, :]
        loc = self.loc[:, None]
        r = self.r
        a2, b2, l2 = (self.a / 2)[:, None], (self.b / 2)[:, None], (self.tiplen / 2)[:, None]
        up = np.sin(0.5 * np.pi * np.clip(u / loc, 0.0, 1.0))
        x = np.clip((u - loc) / (1.0 - loc), 0.0, 1.0)
        down = 1.0 - x * x
        below = u <= loc
        alpha = np.where(below, r + (a2 - r) * up, l2 + (a2 - l2) * down)
        beta = np.where(below, r + (b2 - r) * up, b2 * down)
        return alpha, beta

    def rows_ink(self, sec: Sections) -> np.ndarray:
        """Ink information at the surface rows' axis points V^ (Eq. 21): distance-weighted linear
        interpolation between the two key points that bracket each row along the axis. Returns
        (m, Ns, INK_WIDTH), the fields laid out as INK_FIELDS says."""
        s = self.layout.grid_s
        t = sec.params  # (m, n)
        m, n = t.shape
        j = np.clip(np.sum(t[:, None, :] <= s[None, :, None], axis=2) - 1, 0, n - 2)  # (m, Ns)
        t0 = np.take_along_axis(t, j, 1)
        t1 = np.take_along_axis(t, j + 1, 1)
        w1 = np.clip((s[None, :] - t0) / np.maximum(t1 - t0, 1e-12), 0.0, 1.0)
        w0 = 1.0 - w1

        # every field of a key point stacked into one array, in INK_FIELDS order; vector-mode
        # fields live in the brush frame, the mark works in paper coordinates
        keys = np.concatenate(
            [
                self.wet[..., None],
                self.col,
                self.wr[..., None],
                self.cr[..., None],
                self.wv @ self.R.T,
                self.cv @ self.R.T,
            ],
            axis=2,
        )  # (m, n, INK_WIDTH)
        jj = j[..., None]
        return w0[..., None] * np.take_along_axis(keys, jj, 1) + w1[..., None] * (
            np.take_along_axis(keys, jj + 1, 1)
        )

    # ----------------------------------------------------------------- dynamics (Sec. 5)
    def move(self, pose6, vel6, dt: float):
        """Move the bottom control circle to the virtual position S^t and adjust the middle
        control axes (Sec. 5.2): the current active point (Eq. 13), deformation under the paper
        (Sec. 5.2.2), recovery (Eq. 14)."""
        q = self.q
        B0, R0 = self.B, self.R
        x, y, z, d, qq, rr = (float(v) for v in pose6)
        B1 = np.array([x, y, max(z, 0.0)])
        R1 = rotation_matrix(d, qq, rr)
        lift = B1[2] - B0[2]
        cc = self.cc
        contact = cc[..., 2] <= CONTACT_EPS
        contact[:, 0] = False
        local = (cc - B0) @ R0
        rest = np.zeros_like(local)
        rest[..., 2] = -self.sarc
        krec = min(1.0, q.e * REC_RATE * dt)  # elastic return of free hair (gap, see module doc)
        local = np.where(contact[..., None], local, local + krec * (rest - local))
        carried = B1 + local @ R1.T
        vxy = np.asarray(vel6[:2], dtype=float)
        speed = float(np.hypot(*vxy))
        lag = -vxy / speed if speed > 1e-9 else np.zeros(2)
        # Sec. 5.2.2: hair under the paper travels with the active point (held by friction, sliding
        # a little after the brush), plus dis = e * gamma (in units of r) along the drag
        dis = q.e * self.gamma * self.r * (dt * REF_RATE)
        held = cc.copy()
        held[..., :2] += SLIP * (carried[..., :2] - cc[..., :2]) + dis[:, None, None] * lag
        new = np.where(contact[..., None], held, carried)
        if speed > 1.0:
            self.travel = vxy / speed
        if lift > 0:  # Eq. 14: cz += gamma * |dsz| * tr(dsz)
            new[:, 1:, 2] += self.gamma[:, None] * lift
        new[:, 0] = B1
        self.B, self.R = B1, R1
        self._insert_active_point(new)
        self._constrain(vel6)

    def _insert_active_point(self, new):
        """Eq. 13: the axis's intersection with psi becomes a key point; its ink comes from its
        neighbours by distance-weighted linear interpolation. n stays constant (module doc)."""
        m, n = self.m, self.n
        z = new[..., 2]
        below = z <= CONTACT_EPS
        below[:, 0] = False
        has = below.any(axis=1)
        j = np.where(has, np.argmax(below, axis=1), n)  # first key point on/under the paper
        jj = np.clip(j, 1, n - 1)
        idx = np.arange(m)
        p0, p1 = new[idx, jj - 1], new[idx, jj]
        z0, z1 = p0[:, 2], p1[:, 2]
        lam = np.clip(z0 / np.maximum(z0 - z1, 1e-12), 0.0, 1.0)
        seg = _norm(p1 - p0)
        snap = 0.15 * self.L / (n - 1)
        near_prev = lam * seg < snap
        near_next = (1.0 - lam) * seg < snap
        insert = has & ~near_prev & ~near_next & (z0 > CONTACT_EPS)
        active = np.where(has, np.where(near_prev & (z0 > CONTACT_EPS), jj - 1, jj), -1)
        # snapping to an existing key point: it becomes the active point, on the paper
        snapped = has & ~insert
        new[idx[snapped], active[snapped], 2] = 0.0
        self.cc = new
        if not insert.any():
            self.active = active
            return
        point = p0 + lam[:, None] * (p1 - p0)
        point[:, 2] = 0.0
        # Eq. 13: x_j = (|cc_{j+1} - cc_j| x_{j-1} + |cc_j - cc_{j-1}| x_{j+1})
        #             / |cc_{j+1} - cc_{j-1}|
        w_prev, w_next = 1.0 - lam, lam
        pos = np.where(insert, jj, n)  # rows without insertion append a dummy, dropped again
        ar = np.arange(n + 1)
        src = np.where(ar[None, :] < pos[:, None], ar[None, :], ar[None, :] - 1)
        src = np.clip(src, 0, n - 1)

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

        sarc = extend(self.sarc, interp(self.sarc))
        # drop the interior key point with the smallest arc gap (not first, last or active)
        gap = np.full((m, n + 1), np.inf)
        gap[:, 1:-1] = sarc[:, 2:] - sarc[:, :-2]
        gap[idx, pos] = np.inf
        drop = np.where(insert, np.argmin(gap, axis=1), n)
        keep = ar[None, :] != drop[:, None]

        def shrink(arr):
            return arr[keep].reshape((m, n) + arr.shape[2:])

        self.sarc = shrink(sarc)
        self.cc = shrink(extend(new, point))
        self.col = shrink(extend(self.col, interp(self.col)))
        self.wet = shrink(extend(self.wet, interp(self.wet)))
        self.wv = shrink(extend(self.wv, interp(self.wv)))
        self.cv = shrink(extend(self.cv, interp(self.cv)))
        self.wr = shrink(extend(self.wr, interp(self.wr)))
        self.cr = shrink(extend(self.cr, interp(self.cr)))
        self.active = np.where(insert, np.where(drop < pos, pos - 1, pos), active)

    def _constrain(self, vel6):
        """Hair is inextensible and cannot pass through the paper. Walking from the bottom
        control circle to the tip: a key point too far from its predecessor is pulled after it
        (sliding on the paper); a key point on the paper lies flat at its full arc distance."""
        cc = self.cc
        m, n = self.m, self.n
        shaft = -self.R[:, 2]
        vxy = np.asarray(vel6[:2], dtype=float)
        sp = float(np.hypot(*vxy))
        if np.hypot(shaft[0], shaft[1]) > 0.05:
            fb = np.tile(shaft[:2] / np.hypot(shaft[0], shaft[1]), (m, 1))
        elif sp > 1.0:
            fb = np.tile(-vxy / sp, (m, 1))
        else:  # a vertical brush at rest lays its hair back along the way it came
            fb = np.tile(-self.travel, (m, 1)) + 0.25 * self.lay
            fb /= np.linalg.norm(fb, axis=1, keepdims=True)
        prev = cc[:, 0]
        segs = self.sarc[:, 1:] - self.sarc[:, :-1]
        for j in range(1, n):
            p = cc[:, j]
            d = p - prev
            dist = _norm(d)
            seg = segs[:, j - 1]
            scale = np.minimum(1.0, seg / np.maximum(dist, 1e-12))
            cand = prev + d * scale[:, None]
            on_paper = (p[:, 2] <= CONTACT_EPS) | (cand[:, 2] <= CONTACT_EPS)
            h = np.maximum(prev[:, 2], 0.0)
            reach = on_paper & (seg > h)
            if reach.any():  # lies flat on the paper at its full arc distance
                H = np.sqrt(np.maximum(seg * seg - h * h, 0.0))
                dxy = d[:, :2]
                nd = _norm(dxy)
                dirxy = np.where(nd[:, None] > 1e-9, dxy / np.maximum(nd, 1e-12)[:, None], fb)
                flat = np.zeros((m, 3))
                flat[:, :2] = prev[:, :2] + H[:, None] * dirxy
                p = np.where(reach[:, None], flat, cand)
            else:
                p = cand
            np.maximum(p[:, 2], 0.0, out=p[:, 2])
            cc[:, j] = p
            prev = p

    def contact(self) -> np.ndarray:
        return np.any(self.cc[:, 1:, 2] <= CONTACT_EPS, axis=1)

    def update_stress(self, section_area, section_height, speed, dt):
        """Inner stress (Eq. 10, 11) and pressure (Eq. 12) of every primitive.

        section_area: S_i, bounding-box area of the drawing mark (mm^2); section_height: hei_i,
        distance from the mark to the tip control line's midpoint (mm); speed: |Vel| (mm/s).
        Lengths are made dimensionless by the brush's own size (r, L) so that the quality
        parameters in [0, 1] keep their meaning for any brush."""
        q, r, L, n = self.q, self.r, self.L, self.n
        wet_factor = np.minimum(n / np.maximum(self.wet.sum(axis=1), 1e-9), WET_FACTOR_MAX)
        cone = (section_area / (np.pi * r * r)) * (section_height / L)  # (S*hei/3) / (pi r^2 L/3)
        # Eq. 11: his = hsd + hdd; 1/len is bounded by len >= r/2 (the tip starts as a point)
        hsd = (self.a / self.b) * (0.5 * r) / np.maximum(self.tiplen, 0.5 * r)
        local = (self.cc - self.B) @ self.R
        rest = np.zeros_like(local)
        rest[..., 2] = -self.sarc
        # mc = cc0_1 - cc_1 is zero in the brush frame: its origin is the circle's centre
        disp = _norm(rest[:, 1:] - local[:, 1:])
        seglen = _norm(np.diff(local, axis=1))
        hdd = np.sum(disp * seglen, axis=1) / np.maximum(seglen.sum(axis=1), 1e-12) / L
        his = hsd + hdd
        area = (np.pi * self.a * self.b / 4.0) / (np.pi * r * r)
        self.touching = section_area > 0
        self.stress = (1.0 - q.e) * wet_factor * cone * his * area  # Eq. 10
        self.gamma = (speed / V_REF) * self.stress * q.sm * q.e  # Eq. 12
        return self.stress, self.gamma

    def lose_wetness(self, dt):
        """Eq. 15: wet_{j+-s} -= ab * gamma / 2^(s+d), d = 1 for s = 0 and 2 otherwise. A
        primitive whose section touches the paper without a key point on it loses from its
        lowest key point."""
        touching = self.touching
        if not touching.any():
            return
        act = np.where(self.active >= 0, self.active, np.argmin(self.cc[..., 2], axis=1))
        j = np.arange(self.n)[None, :]
        s = np.abs(j - act[:, None])
        d = np.where(s == 0, 1, 2)
        loss = self.q.ab * self.gamma[:, None] / np.power(2.0, s + d) * (dt * REF_RATE)
        loss = np.where(touching[:, None], loss, 0.0)
        np.maximum(self.wet - loss, 0.0, out=self.wet)

    def adjust_ellipse(self, vel6, dt):
        """Eq. 16 (rotation and elongation of the middle control ellipse at constant hair area),
        Sec. 5.4 (the tip control line follows), Eq. 17 (relocation)."""
        q = self.q
        vel = (np.asarray(vel6[:3], dtype=float) @ self.R) / V_REF  # brush frame, scaled
        touching = self.touching
        eo = self.eori
        per = dt * REF_RATE
        rot = q.re * self.gamma * (eo @ vel) * per  # Eq. 16
        inc = q.ie * self.gamma * _norm(_cross(eo, vel)) * per  # Eq. 16
        rot = np.where(touching, rot, 0.0)
        inc = np.where(touching, inc, 0.0)
        # rotate the minor axis about the shaft
        c, s = np.cos(rot), np.sin(rot)
        ex, ey = eo[:, 0] * c - eo[:, 1] * s, eo[:, 0] * s + eo[:, 1] * c
        self.eori = _unit(np.stack([ex, ey, eo[:, 2]], axis=1))
        area = self.a * self.b
        a = self.a + inc * self.r
        a = np.minimum(a, np.sqrt(area * MAX_FLATNESS))
        # free state: the belly rounds and the tip closes again (gap: elastic return)
        krec = min(1.0, q.e * REC_RATE * dt)
        rnd = np.sqrt(area)
        a = np.where(touching, a, a + krec * (rnd - a))
        self.a = a
        self.b = area / a  # pi a b / 4 constant (Sec. 5.3)
        tl = self.tiplen + inc * self.r  # Sec. 5.4: the tip control line lengthens by inc
        self.tiplen = np.where(touching, np.minimum(tl, 0.5 * self.a), tl * (1.0 - krec))
        # Eq. 17: loc' = nu loc + (1 - nu) (1/n) sum_j arc(P_1..P_{j+1}) / arc(P_1..P_n)
        seg = _norm(np.diff(self.cc, axis=1))
        cum = np.cumsum(seg, axis=1)
        ideal = np.sum(cum / np.maximum(cum[:, -1:], 1e-12), axis=1) / self.n
        new_loc = q.nu * self.loc + (1.0 - q.nu) * ideal
        self.loc = np.clip(np.where(touching, new_loc, self.loc), 0.05, 0.9)

    def split(self):
        """Sec. 5.5: a primitive whose inner stress exceeds tre splits into k = floor(str/tre)
        primitives (Eq. 18), each with 1/k of the hair: a, b / sqrt(k) and len / k (Eq. 19).
        Key points move by rand * (str - tre) (in units of r), rand a random unit vector, growing
        from zero at the shared bottom control circle to full at the tip (hair fans out from the
        ferrule)."""
        tre = max(self.q.tre, 1e-3)
        k = np.floor(self.stress / tre).astype(int)
        k = np.where(self.touching, k, 1)
        room = self.max_primitives - self.m
        k = np.clip(k, 1, None)
        if room <= 0 or not np.any(k >= 2):
            return 0
        extra = k - 1
        # cap the total, taking from the most stressed first (deterministic order)
        order = np.argsort(-self.stress, kind="stable")
        budget = room
        for i in order:
            take = min(extra[i], budget)
            extra[i] = take
            budget -= take
        k = extra + 1
        if not np.any(k >= 2):
            return 0
        reps = k
        src = np.repeat(np.arange(self.m), reps)
        kk = np.repeat(k, reps).astype(float)
        excess = np.repeat(np.maximum(self.stress - tre, 0.0), reps)
        total = len(src)
        dirs = self.rng.normal(size=(total, 3))
        dirs = _unit(dirs)
        split_child = kk > 1
        frac = self.sarc[src] / self.L
        offset = (dirs[:, None, :] * (excess * self.r)[:, None, None]) * frac[..., None]
        offset = np.where(split_child[:, None, None], offset, 0.0)
        self.cc = self.cc[src] + offset
        self.cc[..., 2] = np.maximum(self.cc[..., 2], 0.0)
        self.cc[:, 0] = self.B
        for name in (
            "sarc",
            "col",
            "wet",
            "wv",
            "cv",
            "wr",
            "cr",
            "loc",
            "eori",
            "gamma",
            "stress",
            "active",
            "touching",
        ):
            setattr(self, name, getattr(self, name)[src].copy())
        sq = np.sqrt(kk)
        self.a = self.a[src] / sq  # Eq. 19
        self.b = self.b[src] / sq
        self.tiplen = self.tiplen[src] / kk
        self.hair_u = np.where(
            split_child[:, None], self.rng.random((total, HAIR_BINS)), self.hair_u[src]
        )
        ang = self.rng.random(total) * 2 * np.pi
        self.lay = np.stack([np.cos(ang), np.sin(ang)], axis=1)
        new = int(np.sum(k - 1))
        self.splits += new
        return new

    def ink_flow(self):
        """Eq. 20: each key point's wetness moves toward the mean wetness of the other
        primitives' key points within the diffusion distance eta (in units of the brush's
        diameter), by the share pw."""
        if self.m < 2 or self.q.pw <= 0.0:
            return
        eta = self.q.eta * 2.0 * self.r
        pts = self.cc.reshape(-1, 3)
        wet = self.wet.reshape(-1)
        owner = np.repeat(np.arange(self.m), self.n)
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
        self.wet = (wet * (1.0 - self.q.pw) + mean * self.q.pw).reshape(self.m, self.n)

    def capillary(self, dt):
        """Ink wicks along the axis toward drier key points (gap fill, see module doc)."""
        k = min(0.5, CAP_RATE * dt)
        w = self.wet
        flux = k * 0.5 * (w[:, 2:] - w[:, 1:-1])  # between key points 2..n (not the ferrule)
        if flux.size == 0:
            return
        w[:, 1:-1] += flux
        w[:, 2:] -= flux

    def redraw_streaks(self):
        """Hair bundles whose dryness draw (Eq. 27) changes this step, so streaks have ends."""
        redraw = self.rng.random(self.hair_u.shape) < STREAK_REDRAW
        fresh = self.rng.random(self.hair_u.shape)
        self.hair_u = np.where(redraw, fresh, self.hair_u)

    # ------------------------------------------------------------------ snapshots
    _STATE = (
        "sarc",
        "cc",
        "col",
        "wet",
        "wv",
        "cv",
        "wr",
        "cr",
        "a",
        "b",
        "loc",
        "eori",
        "tiplen",
        "gamma",
        "stress",
        "hair_u",
        "lay",
        "active",
        "touching",
        "travel",
        "B",
        "R",
    )

    def snapshot(self) -> dict:
        snap = {k: np.array(getattr(self, k), copy=True) for k in self._STATE}
        snap["state"] = self.state
        snap["splits"] = self.splits
        return snap

    def restore(self, snap: dict):
        for k in self._STATE:
            setattr(self, k, np.array(snap[k], copy=True))
        self.state = snap["state"]
        self.splits = snap["splits"]
