# SPDX-License-Identifier: GPL-3.0-or-later
"""The same recording, parameters and seed give the same image on any machine (issue 28.2).

numpy picks its SIMD kernels by CPU when it is imported, and OpenBLAS its own; both can be
told to take older ones (NPY_DISABLE_CPU_FEATURES, OPENBLAS_CORETYPE), which stands in for an
older machine. A small character is written in two subprocesses, one under the machine's own
choice, one under the older kernels; the image and the recording must be the same bytes."""

import ctypes
import glob
import math
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

from sim.core import exact
from tests.paths import ROOT

# numpy's and OpenBLAS's own switches, removed from the environment of the machine's own run
SWITCHES = ("NPY_DISABLE_CPU_FEATURES", "NPY_ENABLE_CPU_FEATURES", "OPENBLAS_CORETYPE")
OLD_CORE = "Prescott"  # OpenBLAS's x86-64 kernels without AVX or fused multiply-add


def _dispatched_features() -> list[str]:
    """The CPU features numpy found on this machine beyond its build's baseline (its SIMD
    kernels are picked among these at import)."""
    try:
        from numpy._core._multiarray_umath import __cpu_dispatch__, __cpu_features__
    except ImportError:  # numpy before 2.0
        from numpy.core._multiarray_umath import __cpu_dispatch__, __cpu_features__
    return [f for f in __cpu_dispatch__ if __cpu_features__.get(f)]


def _openblas_core() -> str | None:
    """The name of the kernels OpenBLAS picked in this process, when numpy's BLAS is an
    OpenBLAS that says (None otherwise)."""
    here = os.path.dirname(np.__file__)
    for lib in glob.glob(os.path.join(here, os.pardir, "numpy.libs", "*openblas*")):
        blas = ctypes.CDLL(lib)
        for name in ("openblas_get_corename64_", "scipy_openblas_get_corename64_"):
            f = getattr(blas, name, None)
            if f is not None:
                f.restype = ctypes.c_char_p
                return f().decode()
    return None


def _core_under(env: dict) -> str | None:
    code = "from tests.sim.test_any_machine import _openblas_core; print(_openblas_core())"
    out = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, env=env, capture_output=True, text=True
    )
    return out.stdout.strip() if out.returncode == 0 else None


def _older_machine() -> dict:
    """The environment changes that make this machine an older one: numpy's SIMD kernels and
    OpenBLAS's those of the build's baseline, each where this machine and build let them."""
    out = {}
    features = _dispatched_features()
    if features:
        out["NPY_DISABLE_CPU_FEATURES"] = " ".join(features)
    own_core = _openblas_core()
    if own_core not in (None, "", OLD_CORE):
        if _core_under(_env({"OPENBLAS_CORETYPE": OLD_CORE})) == OLD_CORE:
            out["OPENBLAS_CORETYPE"] = OLD_CORE
    return out


def _env(changes: dict) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in SWITCHES}
    env["PYTHONPATH"] = str(ROOT)
    env["OPENBLAS_NUM_THREADS"] = "1"
    return {**env, **changes}


def _write(tmp_path, name: str, changes: dict) -> tuple[bytes, bytes]:
    """The PNG and the recording of a small write under one setting (its own cache, so that no
    run reads what another made)."""
    out = tmp_path / name.replace(" ", "_")
    out.mkdir()
    env = _env(changes)
    env["XDG_CACHE_HOME"] = str(out / "cache")
    env["HAIRY_BRUSH_CACHE"] = str(out / "cache")
    argv = ["write", "一", "--data", "data/hanzi", "--size", "64", "-q"]
    argv += ["-o", str(out / "a.png"), "--recording", str(out / "a.json")]
    r = subprocess.run(
        [sys.executable, "-m", "sim", *argv], cwd=ROOT, env=env, capture_output=True, text=True
    )
    assert r.returncode == 0, f"{name}: {r.stderr[-2000:]}"
    return (out / "a.png").read_bytes(), (out / "a.json").read_bytes()


def test_a_write_is_the_same_bytes_under_other_cpu_kernels(tmp_path):
    older = _older_machine()
    if not older:
        pytest.skip(
            "neither numpy's SIMD dispatch (no CPU features beyond its baseline) nor "
            f"OpenBLAS's kernel choice (OPENBLAS_CORETYPE={OLD_CORE}) can be changed here"
        )
    with ThreadPoolExecutor(max_workers=2) as pool:
        own = pool.submit(_write, tmp_path, "own", {})
        old = pool.submit(_write, tmp_path, "older", older)
        (png, rec), (old_png, old_rec) = own.result(), old.result()
    assert old_rec == rec, f"the recording differs under {older}"
    assert old_png == png, f"the image differs under {older}"


# --- the deterministic home itself (sim/core/exact.py) ---------------------------------------

RNG_SEED = 28


def _ulps(got, want) -> np.ndarray:
    got, want = np.asarray(got, dtype=float), np.asarray(want, dtype=float)
    return np.abs(got - want) / np.spacing(np.maximum(np.abs(want), 1e-300))


@pytest.mark.parametrize(
    "name, ref, lo, hi",
    [
        ("sin", math.sin, -30.0, 30.0),
        ("cos", math.cos, -30.0, 30.0),
        ("exp", math.exp, -700.0, 700.0),
        ("exp2", lambda v: 2.0**v, -60.0, 60.0),
        ("log", math.log, 1e-6, 1e6),
        ("log1p", math.log1p, -0.999, 10.0),
        ("expm1", math.expm1, -30.0, 30.0),
        ("arcsin", math.asin, -1.0, 1.0),
        ("arccos", math.acos, -1.0, 1.0),
    ],
)
def test_the_transcendentals_take_ieee_arithmetic_only_and_are_near_the_c_library(
    name, ref, lo, hi
):
    """Each array result is the same bits as the same steps on Python floats (IEEE double
    arithmetic with no SIMD kernel to pick), and within 2 units in the last place of the C
    library's."""
    f = getattr(exact, name)
    x = np.random.default_rng(RNG_SEED).uniform(lo, hi, 3000)
    got = f(x)
    one_by_one = np.array([f(v) for v in x.tolist()])
    assert got.view(np.int64).tolist() == one_by_one.view(np.int64).tolist()
    assert _ulps(got, [ref(v) for v in x.tolist()]).max() <= 2.0


def test_arctan2_takes_every_quadrant_as_the_c_library():
    rng = np.random.default_rng(RNG_SEED)
    y, x = rng.normal(size=3000) * 10.0, rng.normal(size=3000)
    y[:4], x[:4] = [0.0, -0.0, 1.0, -1.0], [-1.0, -1.0, 0.0, -0.0]
    got = exact.arctan2(y, x)
    want = [math.atan2(a, b) for a, b in zip(y.tolist(), x.tolist(), strict=True)]
    assert _ulps(got, want).max() <= 1.0
    assert np.array_equal(np.signbit(got), np.signbit(want))
    assert got.tolist() == [
        exact.arctan2(a, b) for a, b in zip(y.tolist(), x.tolist(), strict=True)
    ]


def test_float32_arrays_stay_float32_and_round_from_float64():
    x = np.random.default_rng(RNG_SEED).uniform(-3.0, 3.0, 500).astype(np.float32)
    for name in ("expm1", "exp", "log1p"):
        v = np.abs(x) if name == "log1p" else x
        got = getattr(exact, name)(v)
        assert got.dtype == np.float32
        want = np.array([getattr(math, name)(t) for t in v.astype(float).tolist()])
        assert _ulps(got.astype(float), want.astype(np.float32).astype(float)).max() <= 1.0


@pytest.mark.parametrize(
    "sa, sb",
    [
        ((9, 3), (3, 3)),
        ((3,), (3, 3)),
        ((9, 3), (3,)),
        ((3,), (3,)),
        ((2, 12, 9), (2, 9, 3)),
        ((4, 6, 3, 3), (4, 6, 3, 3)),
        ((5, 3), (3, 1)),
    ],
)
def test_matmul_sums_the_products_in_order(sa, sb):
    """a @ b's shape, each entry a_0 b_0 + a_1 b_1 + ... added left to right (BLAS's kernels
    split and fuse these sums differently from machine to machine)."""
    rng = np.random.default_rng(RNG_SEED)
    a, b = rng.normal(size=sa), rng.normal(size=sb)
    got = exact.matmul(a, b)
    A = a if a.ndim > 1 else a[None]
    B = b if b.ndim > 1 else b[:, None]
    want = A[..., :, 0, None] * B[..., None, 0, :]
    for j in range(1, A.shape[-1]):
        want = want + A[..., :, j, None] * B[..., None, j, :]
    want = want[..., 0, :] if a.ndim == 1 else want
    want = want[..., 0] if b.ndim == 1 else want
    assert np.shape(got) == np.shape(a @ b)
    assert np.asarray(got).tolist() == np.asarray(want).tolist()
    assert np.allclose(got, a @ b, rtol=1e-12, atol=1e-12)
