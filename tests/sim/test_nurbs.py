# SPDX-License-Identifier: GPL-3.0-or-later
import numpy as np
from geomdl import BSpline

from sim.core.nurbs import (
    CIRCLE_KNOTS,
    averaged_knots_one,
    bspline_bases,
    bspline_bases_one,
    bspline_basis,
    chord_params_one,
    circle_points,
    evaluate_nurbs_surface,
    interpolate_cubic,
    surface_control_net,
    to_geomdl,
)


def test_axis_interpolates_key_points_and_matches_geomdl():
    rng = np.random.default_rng(3)
    P = np.cumsum(rng.normal(size=(9, 3)), axis=0)
    ctrl, knots, params = interpolate_cubic(P)
    assert np.allclose(bspline_basis(knots, 3, params) @ ctrl, P, atol=1e-12)
    c = BSpline.Curve()
    c.degree = 3
    c.ctrlpts = ctrl.tolist()
    c.knotvector = knots.tolist()
    u = np.linspace(0, 1, 17)
    ref = np.array(c.evaluate_list(u.tolist()))
    assert np.abs(bspline_basis(knots, 3, u) @ ctrl - ref).max() < 1e-9


def test_basis_partition_of_unity_including_end():
    knots = np.array([0, 0, 0, 0, 0.3, 0.5, 1, 1, 1, 1.0])
    B = bspline_basis(knots, 3, np.linspace(0, 1, 41))
    assert np.allclose(B.sum(axis=1), 1.0)
    assert B[-1, -1] == 1.0


def test_rational_circle_is_exact():
    pts = circle_points(np.linspace(0, 1, 97))
    assert np.abs(np.linalg.norm(pts, axis=1) - 1.0).max() < 1e-12


def _brush_surfaces(brush):
    brush.cc[:, 5:, 0] += np.linspace(0, 6, brush.n - 5)  # a bent axis
    sec = brush.sections()
    return sec, surface_control_net(brush.layout, sec.centres, sec.U, sec.V)


def test_sweep_surface_matches_geomdl_to_1e9(brush):
    sec, net = _brush_surfaces(brush)
    lay = brush.layout
    rng = np.random.default_rng(0)
    u, v = rng.random(200), rng.random(200)
    mine = evaluate_nurbs_surface(net[0], lay.knots_s, 3, CIRCLE_KNOTS, 2, u, v)
    surf = to_geomdl(net[0], lay.knots_s, CIRCLE_KNOTS)
    ref = np.array(surf.evaluate_list(list(zip(u.tolist(), v.tolist(), strict=True))))
    assert np.abs(mine - ref).max() < 1e-9
    # the engine's per-step row form (c + U Cx + V Cy) is the same surface on its grid
    uu, vv = np.meshgrid(lay.grid_s, lay.grid_t, indexing="ij")
    full = evaluate_nurbs_surface(net[0], lay.knots_s, 3, CIRCLE_KNOTS, 2, uu.ravel(), vv.ravel())
    rows = (
        sec.rows_c[0][:, None]
        + sec.rows_U[0][:, None] * lay.ring[None, :, 0, None]
        + sec.rows_V[0][:, None] * lay.ring[None, :, 1, None]
    )
    assert np.abs(rows.reshape(-1, 3) - full).max() < 1e-9


def test_sections_are_the_control_profiles(brush):
    """Bottom control circle of radius r at the base, tip control line (a point) at the tip."""
    sec = brush.sections()
    r = brush.r
    assert np.allclose(np.linalg.norm(sec.U[0, 0]), r) and np.allclose(
        np.linalg.norm(sec.V[0, 0]), r
    )
    assert np.allclose(sec.centres[0, 0], brush.B)
    assert np.linalg.norm(sec.U[0, -1]) < 1e-9 and np.linalg.norm(sec.V[0, -1]) < 1e-9
    # the frames are orthonormal and the profiles lie in the normal planes
    assert np.allclose(np.einsum("msk,msk->ms", sec.U, sec.T), 0, atol=1e-9)
    assert np.allclose(np.einsum("msk,msk->ms", sec.V, sec.T), 0, atol=1e-9)


def test_rotation_minimising_frames_do_not_twist_on_planar_axis(brush):
    """For an axis bent within a plane, an RMF keeps the normal perpendicular to that plane."""
    brush.cc[0, :, 0] += np.linspace(0, 8, brush.n) ** 2 / 8  # bent in the x-z plane
    sec = brush.sections()
    minor = sec.V[0, 1:-1] / np.linalg.norm(sec.V[0, 1:-1], axis=1, keepdims=True)
    major = sec.U[0, 1:-1] / np.linalg.norm(sec.U[0, 1:-1], axis=1, keepdims=True)
    y_comp = np.maximum(np.abs(minor[:, 1]), np.abs(major[:, 1]))
    assert np.all(y_comp > 0.999)


def test_bezier_form_keeps_the_surface_and_matches_blenders_knot_layout(brush):
    from sim.core.nurbs import CIRCLE_KNOTS, evaluate_nurbs_surface

    brush.place([50.0, 50.0, 20.0, 15.0, -10.0, 40.0])
    sec = brush.sections()
    net = surface_control_net(brush.layout, sec.centres, sec.U, sec.V)[0]
    nets, breaks = brush.surface_nets(sec)
    assert nets.shape[1:] == (3 * (len(breaks) - 1) + 1, 9, 4)
    knots = np.concatenate([[0.0], np.repeat(breaks, 3), [1.0]])  # every breakpoint x3
    rng = np.random.default_rng(3)
    u, v = rng.random(200), rng.random(200)
    a = evaluate_nurbs_surface(net, brush.layout.knots_s, 3, CIRCLE_KNOTS, 2, u, v)
    b = evaluate_nurbs_surface(nets[0], knots, 3, CIRCLE_KNOTS, 2, u, v)
    np.testing.assert_allclose(a, b, atol=1e-10)


def test_angles_from_matrix_inverts_rotation_matrix():
    from sim.brush.primitive import angles_from_matrix, rotation_matrix

    rng = np.random.default_rng(0)
    for _ in range(50):
        d, q = rng.uniform(-85, 85, 2)
        r = rng.uniform(-179, 179)
        np.testing.assert_allclose(
            angles_from_matrix(rotation_matrix(d, q, r)), (d, q, r), atol=1e-9
        )


def test_collocation_solve_equals_lapack():
    from sim.core.nurbs import averaged_knots, bspline_basis, chord_params, solve_collocation

    rng = np.random.default_rng(1)
    pts = np.cumsum(rng.random((5, 9, 3)) - 0.3, axis=1)
    params = chord_params(pts)
    N = bspline_basis(averaged_knots(params, 3), 3, params)
    np.testing.assert_allclose(solve_collocation(N, pts), np.linalg.solve(N, pts), atol=1e-12)


def test_the_bezier_net_shape_is_what_surface_nets_returns(brush):
    nets, breaks = brush.surface_nets()
    shape = brush.layout.bezier_net_shape()
    assert nets.shape[1:3] == (shape.points_u, shape.points_v)
    assert shape.points_u == 3 * (len(breaks) - 1) + 1
    assert (shape.order_u, shape.order_v) == (4, 3)  # cubic along the axis, quadratic around


def test_bases_of_one_curve_on_lists_are_the_arrays_bases():
    """Issue 28: ``bspline_bases_one`` (lists in) gives the bits of ``bspline_bases``, zero
    knot spans (repeated key points), parameters at and past the clamped ends included."""
    rng = np.random.default_rng(28)
    for trial in range(200):
        pts = rng.normal(size=(int(rng.integers(4, 12)), 3)).cumsum(axis=0)
        if trial % 3 == 0:
            pts[2] = pts[1]
        pl = chord_params_one(pts.tolist())
        kl = averaged_knots_one(pl, 3)
        at = pl + sorted(rng.random(12).tolist()) + [0.0, 1.0, 1.5, -0.25]
        want = bspline_bases(np.array([kl]), 3, np.array([at]))
        got = bspline_bases_one(kl, 3, at)
        assert len(got) == len(want)
        for g, w in zip(got, want, strict=True):
            assert g.shape == w.shape and g.tobytes() == w.tobytes()
