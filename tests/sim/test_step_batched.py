# SPDX-License-Identifier: GPL-3.0-or-later
"""Issue 28: the engine's faster forms give the same bits as the plain ones - the hair bundles'
distances and laying of many samples' marks at once (``trailpath.signed_distances_many``,
``bristles.across_steps``, ``bristles.lay_steps``) against one sample at a time, and the walk
of ``dynamics.constrain`` on Python floats for one primitive against its arrays' walk."""

import numpy as np
import pytest

from sim.brush import bristles, dynamics, trailpath
from sim.brush.state import BUNDLES
from tests.sim.builders import long_stroke, simulation
from tests.sim.test_trailpath import _mark, _trail


def _step(rng, kind, ppm, s):
    """One sample's marks around its trail's newest point, and its bundles' state."""
    path = _trail(rng, kind, n=int(rng.integers(1, 49)))
    if s % 5 == 4:
        path = path[:1]  # the stroke's first contact: the way the brush goes
    end = path[-1] + rng.normal(0, 0.5, 2)
    m = int(rng.integers(1, 4))
    marks = [
        _mark(rng, i, end + rng.normal(0, 1.0, 2), rng.uniform(0.2, 2.0), ppm) for i in range(m)
    ]
    if s % 7 == 3:
        marks = []
    draws = bristles.draw(rng, m)
    gap = np.where(rng.random((m, BUNDLES)) < 0.5, rng.random((m, BUNDLES)), 0.0)
    st = bristles.BristleState(
        draws["bundle"], gap, draws["edge"], rng.uniform(0.3, 3.0, m), path,
        np.array([0.6, 0.8]), float(rng.uniform(0, 150)),
    )  # fmt: skip
    for mk in marks:
        mk.wet = rng.random(mk.rows.size).astype(np.float32)
        mk.col = rng.random((mk.rows.size, 3)).astype(np.float32)
    return marks, st


KINDS = ["straight", "curve", "zigzag", "still"]


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("ppm", [3.0, 10.24, 20.48])
def test_bundles_of_many_samples_at_once_are_those_of_one_at_a_time(kind, ppm):
    rng = np.random.default_rng([28, KINDS.index(kind), int(ppm * 100)])
    steps = [_step(rng, kind, ppm, s) for s in range(int(rng.integers(4, 12)))]
    marks, states = [m for m, _ in steps], [st for _, st in steps]
    got = bristles.lay_steps(bristles.across_steps(marks, states, ppm), states, ppm)
    assert sum(mk.rows.size for m in marks for mk in m) > 30
    for m, st, g in zip(marks, states, got, strict=True):
        want = bristles.lay(bristles.across(m, st, ppm), st, ppm)
        assert len(g) == len(want)
        for a, b in zip(g, want, strict=True):
            for name in ("lateral", "wet", "col", "skip"):
                x, y = getattr(a, name), getattr(b, name)
                assert (x is None) == (y is None), name
                if x is not None:
                    assert x.dtype == y.dtype and x.tobytes() == y.tobytes(), name


def test_signed_distances_of_many_paths_are_each_paths_own():
    rng = np.random.default_rng(5)
    paths, rows, cols, owner = [], [], [], []
    for s in range(30):
        path = _trail(rng, ["straight", "curve", "zigzag", "still"][s % 4])
        n = int(rng.integers(1, 4000))
        r = (rng.normal(path[-1, 1], 2.0, n) * 10.24).astype(np.int64)
        c = (rng.normal(path[-1, 0], 2.0, n) * 10.24).astype(np.int64)
        paths.append(path), rows.append(r), cols.append(c), owner.append(np.full(n, s))
    got = trailpath.signed_distances_many(
        paths, np.concatenate(owner), np.concatenate(rows), np.concatenate(cols), 10.24
    )
    want = [
        trailpath.signed_distances(p, r, c, 10.24)
        for p, r, c in zip(paths, rows, cols, strict=True)
    ]
    assert got.tobytes() == np.concatenate(want).tobytes()


def _constrain_arrays(brush, vel6):
    """``constrain`` with its arrays' walk: the primitive twice (two rows walk as one)."""
    twin = simulation(long_stroke()[:2], 64, 1.0).brush
    for name in ("cc", "sarc", "lay"):
        setattr(twin, name, np.concatenate([getattr(brush, name)] * 2))
    twin.R, twin.travel = brush.R, brush.travel
    dynamics.constrain(twin, vel6)
    assert twin.cc[0].tobytes() == twin.cc[1].tobytes()
    return twin.cc[:1]


def test_constrain_of_one_primitive_on_floats_is_its_arrays_walk():
    rng = np.random.default_rng(11)
    brush = simulation(long_stroke()[:2], 64, 1.0).brush
    flat = 0
    for trial in range(300):
        n = brush.n
        cc = np.cumsum(rng.normal(0, 1.5, (1, n, 3)), axis=1) + [20.0, 20.0, 3.0]
        cc[..., 2] = np.where(rng.random((1, n)) < 0.4, rng.choice([0.0, -0.0, -0.3]), cc[..., 2])
        if trial % 2:
            cc[0, 0, 2] = -0.0  # the base on the paper (signed zeros keep their signs)
        brush.cc = cc
        brush.sarc = np.cumsum(rng.uniform(0.5, 4.0, (1, n)), axis=1) - 0.5
        brush.R = np.eye(3) if trial % 3 else dynamics.rotation_matrix(20.0, 10.0, 0.0)
        brush.travel = np.array([0.0, 1.0])
        vel = rng.normal(0, 30.0, 6) * (trial % 4 != 0)
        want = _constrain_arrays(brush, vel)
        dynamics.constrain(brush, vel)
        assert brush.cc.tobytes() == want.tobytes()
        flat += int(np.count_nonzero(brush.cc[..., 2] == 0.0))
    assert flat > 100  # hair lay flat on the paper


def test_one_collocation_system_on_floats_is_the_arrays_elimination():
    """``solve_collocation`` of one system (Python floats) against a stack of two (arrays)."""
    from sim.core import nurbs

    rng = np.random.default_rng(3)
    for trial in range(400):
        n = int(rng.integers(4, 14))
        pts = np.cumsum(rng.normal(size=(1, n, 3)) * rng.uniform(0.01, 5.0), axis=1)
        if trial % 5 == 0:
            pts[0, :, 2] = np.where(rng.random(n) < 0.5, -0.0, pts[0, :, 2])
        params = nurbs.chord_params(pts)
        A = nurbs.bspline_basis(nurbs.averaged_knots(params, 3), 3, params)
        one = nurbs.solve_collocation(A, pts)
        two = nurbs.solve_collocation(np.concatenate([A, A]), np.concatenate([pts, pts]))
        assert one.shape == pts.shape and one.tobytes() == two[:1].tobytes()


def test_a_banded_collocation_system_skips_its_zeros_bit_for_bit():
    """``_solve_one`` with ``band`` (no -0.0 in the system: a row outside the band left as
    it is) gives the full elimination's bytes, zeros' signs included."""
    from sim.core import nurbs

    rng = np.random.default_rng(5)
    zeros = 0
    for trial in range(400):
        n = int(rng.integers(4, 14))
        pts = np.cumsum(rng.normal(size=(n, 3)) * rng.uniform(0.01, 5.0), axis=0)
        if trial % 3 == 0:
            pts[rng.random(n) < 0.5, 2] = 0.0  # hair lying on the paper
        params = nurbs.chord_params(pts)
        A = nurbs.bspline_basis(nurbs.averaged_knots(params, 3), 3, params)
        assert not nurbs._negative_zero(A) and not nurbs._negative_zero(pts)
        full = np.array(nurbs._solve_one(A.tolist(), pts.tolist(), band=False))
        band = np.array(nurbs._solve_one(A.tolist(), pts.tolist(), band=True))
        assert band.tobytes() == full.tobytes()
        zeros += int(np.count_nonzero(A == 0.0))
    assert zeros > 1000  # the systems were banded: rows were skipped


def test_the_edges_crossing_the_paper_are_the_ends_of_cur_u():
    """``mark.edge_crossings`` (what the dynamics take of a cut) gives exactly the ends of the
    marching squares' segments (``slice_grids``, joined later for the marks), grid by grid."""
    from sim.brush import mark

    rng = np.random.default_rng(17)
    saddles = 0
    for _ in range(60):
        X = rng.normal(size=(int(rng.integers(1, 4)), int(rng.integers(2, 9)), 24, 3))
        X[..., 2] += rng.uniform(-1.0, 1.0)
        pts, grid = mark.edge_crossings(X)
        segs, owner = mark.slice_grids(X)
        for g in range(len(X)):
            ends = {tuple(p) for p in segs[owner == g][:, :, :2].reshape(-1, 2).tolist()}
            assert {tuple(p) for p in pts[grid == g].tolist()} == ends
        inw = X[..., 2] <= 0
        saddles += int(np.count_nonzero(inw[:, :-1, :-1] & inw[:, 1:, 1:] & ~inw[:, :-1, 1:]))
    assert saddles > 0
