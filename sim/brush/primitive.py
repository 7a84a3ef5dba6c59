# SPDX-License-Identifier: GPL-3.0-or-later
"""The virtual hairy brush HB = (CWP, Qp) (Eq. 1): writing primitives (Sec. 3.2), their swept
solid and the brush states (Sec. 3.3-3.6), and the entry points of the dynamic adjustments
(Sec. 5, in ``dynamics``).

All m writing primitives share one set of arrays: key points are ``(m, n, ...)`` (every primitive
has the same number n of key points, as the paper's split keeps it, Sec. 5.5), so every step is
vectorised over primitives and key points.

The fields of a primitive and its key points (and a glossary of the paper's symbols used as
their names: cc, sarc, wr, cr, wv, cv, eori, ...) are declared once in ``brush_state``; the
dynamics (Sec. 5) are in ``dynamics``, the ink (Sec. 3.2.3, 3.5) in ``brush_ink``; this module
holds the brush's geometry (Sec. 2, 3.2-3.4) and its steps' entry points.

Coordinates are millimetres in the paper's frame: x to the right, y up the sheet, z up from the
paper plane psi (z = 0). The brush's local frame (Fig. 2(c)) has the bottom control circle as
its x-y plane, its centre as the origin and the shaft as +z; the free hair hangs along -z.
Its orientation is R = Rx(q) Ry(d) Rz(r): r turns the brush about its handle, d deflects it
sideways (about the paper's y axis), q forward (about the x axis).

Gaps in the paper, filled as a real brush behaves (each also noted where it is implemented):
- Key points are material points of the hair, each with its arc coordinate (``sarc``) along
  the hair; the hair is inextensible. Key points never pass through the paper; a key point pressed
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

import math
from dataclasses import dataclass

import numpy as np

from ..core import exact
from ..core.exact import matmul
from ..core.frames import angles_from_matrix, clip, cross, rotation_matrix, unit
from ..core.nurbs import (
    SweepLayout,
    averaged_knots,
    averaged_knots_one,
    bezier_form,
    bspline_bases,
    bspline_bases_one,
    chord_params,
    chord_params_one,
    derivative_ctrl,
    derivative_ctrl_one,
    einsum,
    rotation_minimising_frames,
    solve_collocation,
    solve_collocation_one,
    surface_control_net,
)
from ..core.params import BrushGeometry, InkSpec, QualityParams
from . import bristles, dynamics
from . import ink as brush_ink
from . import state as brush_state
from .bristles import draw as draw_bundles

__all__ = ["HairyBrush", "Sections", "angles_from_matrix", "rotation_matrix"]
MAX_PRIMITIVES = 32  # the split stops adding primitives here (Sec. 5.5)
_NO_ANGLE = np.array([0.0, 1.0])  # (cos, sin) of the ellipse's angle when it has none


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
    """The brush: collection of writing primitives WP_i = (C_i, E_i, L_i, A_i) plus Qp. Its
    fields (``brush_state.FIELDS``) are plain attributes: ``brush.wet[0, 3]`` is the wetness of
    the first primitive's fourth key point."""

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
        self.trail = bristles.new_trail()  # the contact's recent path on the paper (bristles)
        self.splits = 0
        self.max_primitives = MAX_PRIMITIVES
        self._free_state(1)

    # ----------------------------------------------------------------- states (Sec. 3.3-3.5)
    def _free_state(self, m: int, a=None, b=None):
        """Sec. 3.4: axis a straight line, ellipse a circle, tip line a point."""
        n, L, g = self.n, self.L, self.geometry
        brush_state.blank(self, m)
        self.sarc = np.tile(np.linspace(0.0, L, n), (m, 1))
        self.cc = self._rest_world(self.sarc, self.B, self.R)
        d = g.belly_diameter_mm
        self.a = np.full(m, d if a is None else a)
        self.b = np.full(m, d if b is None else b)
        self.loc = np.full(m, g.belly_loc)
        self.eori = np.tile([0.0, 1.0, 0.0], (m, 1))  # minor axis orientation, brush frame
        for name, value in draw_bundles(self.rng, m).items():  # hair bundles (bristles)
            setattr(self, name, value)
        ang = self.rng.random(m) * 2 * np.pi
        self.lay = np.stack(exact.sin_cos(ang)[::-1], axis=1)

    @property
    def m(self) -> int:
        return self.cc.shape[0]

    @staticmethod
    def _rest_world(sarc, B, R):
        local = np.zeros(sarc.shape + (3,))
        local[..., 2] = -sarc
        return B + matmul(local, R.T)

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
        """Dipping state (Sec. 3.5, Eq. 7-8), see ``brush_ink.dip``."""
        brush_ink.dip(self, ink, depth, color, wetness)

    # ---------------------------------------------------------------------------- geometry
    def sections(self) -> Sections:
        """Sweep the bottom control circle, middle control ellipse and tip control line along
        the middle control axis (Sec. 2, 3.2) with rotation-minimising frames."""
        lay = self.layout
        u = lay.station_u
        params, bases, ctrl, dq = self._middle_axis(u)
        m, n = params.shape
        centres = matmul(bases[3][:, n:], ctrl)
        # the derivative's basis is degree 2 on knots[1:-1]
        T = unit(matmul(bases[2][:, n:, 1:-1], dq))
        frames = np.empty((m, len(u), 2, 3))  # the normals N and binormals Bn side by side
        N = frames[:, :, 0]
        N[...] = rotation_minimising_frames(centres, T, self._first_normal(T))
        Bn = frames[:, :, 1]
        Bn[...] = cross(T, N)
        cos_v, sin_v = self._ellipse_angle(u, frames)
        vhat = cos_v * N + sin_v * Bn  # minor axis direction
        uhat = sin_v * N - cos_v * Bn  # major axis direction
        alpha, beta = self.profile_semiaxes(u)
        U = alpha[..., None] * uhat
        V = beta[..., None] * vhat
        # the surface rows from the stations: one product for the four fields side by side
        # (every element is the same sum over the stations, in the same order, as four)
        at_rows = einsum(
            "ij,mjk->mik", lay.row_from_station, np.concatenate([centres, U, V, T], axis=2)
        )
        rows_c, rows_U, rows_V = (at_rows[..., k : k + 3].copy() for k in (0, 3, 6))
        rows_T = unit(at_rows[..., 9:12])  # a new array already
        return Sections(centres, U, V, T, params, rows_c, rows_U, rows_V, rows_T)

    def _first_normal(self, T):
        """The frames' initial normal: the bottom control circle's own x axis (cori = shaft
        direction) made perpendicular to the axis's first tangent."""
        x0 = self.R[:, 0]
        if self.m == 1:
            return _first_normal_one(T[0, 0].tolist(), x0.tolist(), self.R[:, 1])
        r0 = x0 - einsum("ij,j->i", T[:, 0], x0)[:, None] * T[:, 0]
        return unit(r0, fallback=self.R[:, 1])

    def _ellipse_angle(self, u, frames):
        """Orientation of the middle control ellipse (Eq. 6): its minor axis eori, projected
        into the normal plane at loc, fixes the profiles' angle within the swept frames:
        (cos, sin) of its angle from N at loc (cos 0, sin 1 where it is about the axis), each
        (m, 1, 1) to scale the frames' (m, stations, 3) vectors."""
        m = self.m
        ks = clip(u.searchsorted(self.loc), 0, len(u) - 1)
        if m == 1:
            return _ellipse_angle_one(self.eori[0].tolist(), self.R.tolist(), frames[0, ks[0]])
        minor = matmul(self.eori, self.R.T)
        cs = einsum("ij,ikj->ik", minor, frames[np.arange(m), ks])
        h = np.hypot(cs[:, 0], cs[:, 1])[:, None]
        cs = np.where(h > 1e-9, cs / np.maximum(h, 1e-12), _NO_ANGLE)[:, None, :, None]
        return cs[:, :, 0], cs[:, :, 1]

    def _middle_axis(self, u):
        """A_i through P_i,1..n (Sec. 3.2.3), as ``interpolate_cubic``: the key points'
        parameters, the basis at them (the collocation matrix) and at the stations ``u`` in one
        recursion (every parameter's basis is its own: the same numbers as two), the control
        points and those of the derivative. One primitive's parameters, knots and control
        points are made on Python floats (``chord_params_one`` ...: the same numbers, without
        a numpy call each; issue 28)."""
        if self.m == 1:
            pl = chord_params_one(self.cc[0].tolist())
            kl = averaged_knots_one(pl, 3)
            params = np.array([pl])
            bases = bspline_bases_one(kl, 3, pl + u.tolist())
            n = len(pl)
            cl = solve_collocation_one(bases[3][0, :n], self.cc[0])
            return params, bases, np.array([cl]), np.array([derivative_ctrl_one(cl, kl, 3)])
        params = chord_params(self.cc)
        knots = averaged_knots(params, 3)
        m, n = params.shape
        at = np.empty((m, n + len(u)))  # the key points' parameters, then the stations'
        at[:, :n] = params
        at[:, n:] = u
        bases = bspline_bases(knots, 3, at)
        ctrl = solve_collocation(bases[3][:, :n], self.cc)
        return params, bases, ctrl, derivative_ctrl(ctrl, knots, 3)[0]

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
        if self.m == 1 and 0.0 < float(self.loc[0]) < 1.0:
            return self._profile_semiaxes_one(np.asarray(u, dtype=float).tolist())
        u = np.asarray(u)[None, :]
        loc = self.loc[:, None]
        r = self.r
        a2, b2, l2 = (self.a / 2)[:, None], (self.b / 2)[:, None], (self.tiplen / 2)[:, None]
        up = exact.sin(0.5 * np.pi * clip(u / loc, 0.0, 1.0))
        x = clip((u - loc) / (1.0 - loc), 0.0, 1.0)
        down = 1.0 - x * x
        below = u <= loc
        alpha = np.where(below, r + (a2 - r) * up, l2 + (a2 - l2) * down)
        beta = np.where(below, r + (b2 - r) * up, b2 * down)
        return alpha, beta

    def _profile_semiaxes_one(self, u: list):
        """``profile_semiaxes`` of the one primitive (0 < loc < 1) on Python floats, station
        by station: the same operations on the same numbers, without a numpy call each (the
        brush's step on a dozen numbers; issue 28)."""
        loc, r = float(self.loc[0]), self.r
        a2, b2, l2 = float(self.a[0]) / 2, float(self.b[0]) / 2, float(self.tiplen[0]) / 2
        alpha, beta = [], []
        for s in u:
            if s <= loc:
                up = exact.sin(0.5 * np.pi * _clip01(s / loc))
                alpha.append(r + (a2 - r) * up)
                beta.append(r + (b2 - r) * up)
            else:
                x = _clip01((s - loc) / (1.0 - loc))
                down = 1.0 - x * x
                alpha.append(l2 + (a2 - l2) * down)
                beta.append(b2 * down)
        return np.array([alpha]), np.array([beta])

    def rows_ink(self, sec: Sections) -> np.ndarray:
        """The ink at the surface rows' axis points V^ (Eq. 21), see ``brush_ink.rows_ink``:
        (m, Ns, INK_WIDTH), the fields laid out as INK_FIELDS says."""
        return brush_ink.rows_ink(self, sec)

    # ------------------------------------------------------------ dynamics (Sec. 5, ``dynamics``)
    def move(self, pose6, vel6, dt: float):
        """The bottom control circle to the virtual position; the hair follows (Sec. 5.2, Eq. 13,
        14)."""
        dynamics.move(self, pose6, vel6, dt)

    def _insert_active_point(self, new):
        """Eq. 13: the axis's crossing with psi becomes a key point."""
        dynamics.insert_active_point(self, new)

    def update_stress(self, section_area, section_height, speed, dt):
        """Inner stress (Eq. 10, 11) and pressure (Eq. 12); returns (stress, gamma)."""
        return dynamics.update_stress(self, section_area, section_height, speed, dt)

    def lose_wetness(self, dt):
        """Eq. 15."""
        dynamics.lose_wetness(self, dt)

    def adjust_ellipse(self, vel6, dt):
        """Eq. 16 (rotation and elongation), Sec. 5.4 (tip line), Eq. 17 (relocation)."""
        dynamics.adjust_ellipse(self, vel6, dt)

    def split(self) -> int:
        """Sec. 5.5, Eq. 18-19; returns the number of new primitives."""
        return dynamics.split(self)

    def split_under(self, stress: float) -> int:
        """Split as if every primitive pressed the paper with inner stress ``stress`` (Eq. 18
        with the brush's tre: k = floor(stress / tre)), for benchmarks and tests that want a
        split brush. Returns the number of new primitives (``max_primitives`` caps them)."""
        self.touching[:] = True
        self.stress[:] = stress
        new = self.split()
        self.touching[:] = False
        return new

    def ink_flow(self):
        """Eq. 20."""
        dynamics.ink_flow(self)

    def capillary(self, dt):
        """Ink wicks along the axis toward drier key points (module doc)."""
        dynamics.capillary(self, dt)

    def follow(self, contact_xy):
        """The hair's contact with the paper is at ``contact_xy`` (mm): its path, the trail
        the hair bundles are drawn along (``bristles``), begins anew where the hair comes
        down on the paper (no primitive touched it the step before)."""
        fresh = not self.touching.any()
        self.trail = bristles.extend_trail(self.trail, contact_xy, fresh)

    def step_bundles(self, speed, dt):
        """The hair bundles' dry-brush draws and gaps after this step (``bristles``)."""
        bristles.step(self, speed, dt)

    # ------------------------------------------------------------------ snapshots
    def snapshot(self) -> dict:
        """Every field, the pose, the state and the split count (``restore`` takes it back)."""
        return brush_state.snapshot(self)

    def restore(self, snap: dict):
        brush_state.restore(self, snap)


def _clip01(x: float) -> float:
    """np.clip(x, 0, 1) of a Python float: the same picks (max, then min, as numpy's clip)."""
    x = x if x > 0.0 else 0.0
    return x if x < 1.0 else 1.0


def _einsum_dot3(a, b) -> float:
    """The dot product of two 3-vectors (Python floats) as np.einsum sums it: from zero, the
    products of x, then z, then y (issue 28)."""
    return ((0.0 + a[0] * b[0]) + a[2] * b[2]) + a[1] * b[1]


def _first_normal_one(t, x0, fallback):
    """``_first_normal`` of one primitive on Python floats: its first tangent ``t`` and the
    circle's x axis ``x0`` (lists), the same operations as the arrays' (``unit``'s length
    summed x, y, z); an array (1, 3)."""
    d = _einsum_dot3(t, x0)
    r = [x0[0] - d * t[0], x0[1] - d * t[1], x0[2] - d * t[2]]
    n = math.sqrt((r[0] * r[0] + r[1] * r[1]) + r[2] * r[2])
    if not n > 1e-9:
        return np.array([fallback])
    return np.array([[r[0] / n, r[1] / n, r[2] / n]])


def _ellipse_angle_one(eori, R, frame):
    """``_ellipse_angle`` of one primitive: its minor axis ``eori`` (a list, brush frame), the
    rotation R (rows) and the frame (N, Bn) at loc; the minor axis in the world as
    ``exact.matmul`` sums it (over 0, 1, 2), the products with N and Bn as np.einsum's."""
    e0, e1, e2 = eori
    minor = [(e0 * r[0] + e1 * r[1]) + e2 * r[2] for r in R]
    fn, fb = frame.tolist()
    c, s = _einsum_dot3(minor, fn), _einsum_dot3(minor, fb)
    h = float(np.hypot(c, s))
    if not h > 1e-9:
        return float(_NO_ANGLE[0]), float(_NO_ANGLE[1])
    return c / h, s / h
