# SPDX-License-Identifier: GPL-3.0-or-later
"""Configuring the brush automatically (Sec. 7.2): fit the quality parameters to training
samples by minimising Eq. 28.

A training sample is a recording (the 6-DOF strokes a student wrote) and the image it should
have made (S^i: strokes inside given boundaries, the "MiaoHong" practice). The target function
(Eq. 28) sums |dr| + |dg| + |db| over every pixel of every sample between S^i and the brush's
result C^i; here it is divided by the number of pixels, so it reads as the mean per-pixel
difference (0 = identical, 3 = black against white everywhere).

The search (Sec. 7.2): Qp1 (e, tre, nu, re, ie, sm) first, with Qp2 = 0 (no dry brush, no
diffusion), then Qp2 (ren, eta, ab, pw, dry) with Qp1 fixed. Each stage divides the edges of the
current cube into d parts, evaluates the grid points (and any preset given as a seed), and runs
steepest descent - forward-difference gradient, line search along the descent direction - from
the best few of them, in parallel processes; the cube then shrinks to [x - 1/d, x + 1/d] around
the grid point nearest the best solution, and the procedure repeats until the target stops
improving by more than the error bound or the rounds run out. Every evaluation is a seeded
simulation and the parallel results are gathered in a fixed order, so a fit is deterministic.
"""

from __future__ import annotations

import json
import os
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..core.files import write_atomic
from ..core.jsonio import read_json
from ..core.params import QP1, QP2, ParameterError, QualityParams, number_within, short_repr
from ..core.recording import MAX_SEED
from .cluster import exit_with_parent
from .samples import TrainingSample
from .target import _init_worker, target_function


@dataclass
class FitSettings:
    # the defaults of every fit: the command line's options and Blender's Fit Parameters read them
    divisions: int = 1  # d: edge divisions of the cube (grid of (d + 1)^k points)
    starts: int = 0  # descents per round (0: one per worker)
    rounds: int = 2  # cube shrinks
    iterations: int = 6  # steepest-descent steps per descent
    step: float = 0.05  # finite-difference step (Delta x_i), as a share of the cube's edge
    line_steps: int = 6  # line search: lambda_max, lambda_max / 2, ... this many values
    error_bound: float = 1e-3  # stop when a round improves the target by less than this
    grad_bound: float = 1e-3  # epsilon of step 2: stop a descent when |y| is smaller
    workers: int = 0  # processes (0: all cores)
    max_grid: int = 64  # at most this many grid points are evaluated per round
    seed: int = 0  # draws the grid subset
    stages: tuple = ("qp1", "qp2")
    only: tuple = ()  # fit just these parameters (the others keep the seed's values)
    # {name: (lo, hi)}: a parameter's search interval inside [0, 1] (all of it when not named);
    # e.g. e <= 0.97 keeps some rigidity (1 - e) in the hair, so Eq. 10's stress and with it
    # the pressure of Eq. 12 and the texture that follows from it (Eq. 15, 16, 27) stay on
    bounds: dict = field(default_factory=dict)
    # evaluate on a Dask cluster: "local" (a LocalCluster here) or a scheduler's address; the
    # result is the same as without, for the same workers (or starts)
    scheduler: str | None = None

    def __post_init__(self):
        for name, (lo, hi) in SETTING_RANGES.items():
            v = getattr(self, name)
            whole = name not in ("step", "error_bound", "grad_bound")
            if (whole and (isinstance(v, bool) or not isinstance(v, int))) or not number_within(
                v, lo, hi
            ):
                kind = "a whole number" if whole else "a number"
                raise ParameterError(
                    f"fit setting '{name}' must be {kind} in [{lo}, {hi}], got {short_repr(v)}"
                )
        stages, only = tuple(self.stages), tuple(self.only)
        if not stages or any(st not in ("qp1", "qp2") for st in stages):
            raise ParameterError(
                f"fit setting 'stages' must name qp1 and/or qp2, got {list(stages)!r}"
            )
        if any(n not in QP1 + QP2 for n in only):
            raise ParameterError(f"fit setting 'only' names unknown parameters: {list(only)!r}")
        self.stages, self.only = stages, only
        bounds = self.bounds if isinstance(self.bounds, dict) else {None: self.bounds}
        for n, b in bounds.items():
            pair = isinstance(b, (tuple, list)) and len(b) == 2
            ok = pair and n in QP1 + QP2 and all(number_within(v, 0.0, 1.0) for v in b)
            if not ok or b[0] >= b[1]:
                raise ParameterError(
                    "fit setting 'bounds' must map quality names to [lo, hi] with 0 <= lo < hi "
                    f"<= 1, got {short_repr({n: b})}"
                )

    def box(self, names) -> tuple[np.ndarray, np.ndarray]:
        """The search box of these parameters: [0, 1] each, or its bound."""
        lo = np.array([float(self.bounds.get(n, (0.0, 1.0))[0]) for n in names])
        hi = np.array([float(self.bounds.get(n, (0.0, 1.0))[1]) for n in names])
        return lo, hi


# the fit's settings: [lowest, highest] (a grid of (divisions + 1)^6 points is drawn from)
SETTING_RANGES = {
    "divisions": (1, 8),
    "starts": (0, 256),
    "rounds": (1, 100),
    "iterations": (0, 1000),
    "step": (1e-6, 1.0),
    "line_steps": (1, 64),
    "error_bound": (0.0, 3.0),
    "grad_bound": (0.0, 1e6),
    "workers": (0, 256),
    "max_grid": (1, 10_000),
    "seed": (0, MAX_SEED),
}


@dataclass
class FitResult:
    quality: dict
    target: float  # Eq. 28 (mean per pixel) at the result
    start_target: float  # at the seed
    evaluations: int
    history: list = field(default_factory=list)

    def to_preset(self, name: str, label: str = "", description: str = "") -> dict:
        return {
            "kind": "quality",
            "label": label or name,
            "description": description
            or f"Fitted by sim fit (Eq. 28: {self.start_target:.4f} -> {self.target:.4f})",
            "quality": {k: round(float(v), 4) for k, v in self.quality.items()},
            "fit": {
                "target": self.target,
                "start_target": self.start_target,
                "evaluations": self.evaluations,
            },
        }


# ---------------------------------------------------------------- steepest descent (Sec. 7.2)
def _values(names, x, fixed) -> dict:
    return {**fixed, **{n: float(v) for n, v in zip(names, x, strict=True)}}


def descend(names, x0, lo, hi, fixed, settings: FitSettings, f0=None, stage=None):
    """Steepest descent from x0 inside the box [lo, hi]: y = -grad (forward differences, a
    backward one at the upper face), lambda by a line search over halving steps from the
    longest step that stays in the box; stops when |y| < epsilon, no step improves, or after
    ``settings.iterations`` steps. Returns (x, f, evaluations). The paper writes the difference
    quotient as theta(X + dx) / dx; the forward difference (theta(X + dx) - theta(X)) / dx is
    meant."""
    x = np.asarray(x0, dtype=float)
    f = target_function(_values(names, x, fixed), stage=stage) if f0 is None else f0
    evals = 0 if f0 is not None else 1
    # the difference step scales with the current cube, so a shrunken cube probes finer
    h = np.maximum(settings.step * (hi - lo), 1e-3)
    for _ in range(settings.iterations):
        g = np.zeros(len(x))
        for i in range(len(x)):
            xi = x.copy()
            sgn = 1.0 if x[i] + h[i] <= hi[i] else -1.0
            xi[i] = x[i] + sgn * h[i]
            g[i] = sgn * (target_function(_values(names, xi, fixed), stage=stage) - f) / h[i]
            evals += 1
        y = -g
        # a face of the box that y pushes against is held
        y = np.where(((x <= lo) & (y < 0)) | ((x >= hi) & (y > 0)), 0.0, y)
        norm = float(np.linalg.norm(y))
        if norm < settings.grad_bound:
            break
        u = y / norm
        with np.errstate(divide="ignore", invalid="ignore"):
            reach = np.where(u > 0, (hi - x) / u, np.where(u < 0, (lo - x) / u, np.inf))
        lam_max = float(min(np.min(reach), 0.5 * np.max(hi - lo)))
        best = (f, None)
        lam = lam_max
        for _ in range(settings.line_steps):  # line search: lambda_max, /2, /4, ...
            if lam < 1e-4:
                break
            xn = np.clip(x + lam * u, lo, hi)
            fn = target_function(_values(names, xn, fixed), stage=stage)
            evals += 1
            if fn < best[0]:
                best = (fn, xn)
            lam *= 0.5
        if best[1] is None:
            break
        f, x = best[0], best[1]
    return x, f, evals


def _descend_task(args):
    names, x0, lo, hi, fixed, settings, f0, stage = args
    x, f, evals = descend(
        names, np.asarray(x0), np.asarray(lo), np.asarray(hi), fixed, settings, f0, stage
    )
    return x.tolist(), f, evals


def _eval_task(args):
    names, x, fixed, stage = args
    return target_function(_values(names, x, fixed), stage=stage)


class _Pool:
    """Runs tasks in worker processes (or in this one for workers = 1), results in order."""

    def __init__(self, samples, workers: int):
        self.workers = workers
        self.samples = samples
        self.ex = None
        if workers > 1:
            self.ex = ProcessPoolExecutor(
                workers, initializer=_init_pool_worker, initargs=(os.getpid(), samples)
            )
        _init_worker(samples)

    def map(self, fn, tasks):
        if self.ex is None:
            return [fn(t) for t in tasks]
        return list(self.ex.map(fn, tasks))

    def close(self):
        if self.ex is not None:
            self.ex.shutdown()


def _pool(samples, workers: int, scheduler: str | None):
    """The local process pool, or a Dask cluster's (``cluster``) when a scheduler is named."""
    if scheduler is None:
        return _Pool(samples, workers)
    from .cluster import DaskPool

    return DaskPool(samples, scheduler, workers, _init_worker)


@dataclass
class _Round:
    """One round of Sec. 7.2 in the cube [lo, hi]: the grid's points evaluated, steepest
    descents from the best of them (and from the best so far), the best result kept."""

    names: tuple
    lo: np.ndarray
    hi: np.ndarray
    fixed: dict
    stage: str
    settings: FitSettings
    starts: int

    def run(self, pool, rng, best_x, best_f):
        """(best x, best Eq. 28, evaluations made)."""
        names, lo, hi, fixed, stage = self.names, self.lo, self.hi, self.fixed, self.stage
        d = max(int(self.settings.divisions), 1)
        grid = _grid(lo, hi, d, self.settings.max_grid, rng)
        fs = pool.map(_eval_task, [(names, g.tolist(), fixed, stage) for g in grid])
        evaluations = len(grid)
        cands = [(f, i, g) for i, (f, g) in enumerate(zip(fs, grid, strict=True))]
        cands.sort(key=lambda c: (c[0], c[1]))
        starts_x = [(best_x, best_f)] + [(g, f) for f, _, g in cands[: self.starts - 1]]
        tasks = [(names, x.tolist(), lo, hi, fixed, self.settings, f, stage) for x, f in starts_x]
        for x, f, ev in pool.map(_descend_task, tasks):
            evaluations += ev
            if f < best_f:
                best_f, best_x = f, np.asarray(x)
        return best_x, best_f, evaluations


def _grid(lo, hi, d: int, limit: int, rng: np.random.Generator):
    """Grid points of the box [lo, hi] with d divisions per edge (corners of the subcubes); when
    there are more than ``limit``, a subset drawn by the fit's seeded generator."""
    axes = [np.linspace(a, b, d + 1) for a, b in zip(lo, hi, strict=True)]
    total = (d + 1) ** len(axes)
    which = np.arange(total)
    if total > limit:
        which = np.sort(rng.choice(total, size=limit, replace=False))
    # the points in itertools.product's order (the last axis fastest), only the drawn ones
    idx = np.unravel_index(which, (d + 1,) * len(axes))
    return np.stack([ax[i] for ax, i in zip(axes, idx, strict=True)], axis=1)


def fit(
    samples: list[TrainingSample],
    seed_quality: dict | None = None,
    settings: FitSettings | None = None,
    progress=None,
) -> FitResult:
    """Fit the quality parameters to the training samples (Sec. 7.2, Eq. 28), starting from
    ``seed_quality`` (a preset's values, say); parameters it does not name start from the first
    training recording's own values."""
    if not samples:
        raise ParameterError("fit needs at least one training sample")
    settings = settings or FitSettings()
    workers = settings.workers or os.cpu_count() or 1
    starts = settings.starts or workers
    # values not given by the seed are the ones the (first) training recording already uses
    seed = samples[0].recording.resolve()[0].to_dict()
    if seed_quality:
        checked = QualityParams().with_values(seed_quality).to_dict()
        seed.update({k: checked[k] for k in seed_quality})
    pool = _pool(samples, workers, settings.scheduler)
    rng = np.random.Generator(np.random.PCG64(settings.seed))
    evaluations = 0
    history = []
    try:
        start_target = target_function(seed, samples)
        evaluations += 1
        current = dict(seed)
        stages = [s for s in settings.stages if s in ("qp1", "qp2")]
        total_rounds = max(len(stages) * settings.rounds, 1)
        done_rounds = 0
        for stage in stages:
            names = QP1 if stage == "qp1" else QP2
            if settings.only:
                names = tuple(n for n in names if n in settings.only)
                if not names:
                    continue
            # Sec. 7.2: while fitting Qp1, Qp2 = 0 (no dry brush, no diffusion)
            fixed = {k: v for k, v in current.items() if k not in names}
            if stage == "qp1":
                fixed.update({k: 0.0 for k in QP2})
            lo, hi = settings.box(names)
            outer = (lo.copy(), hi.copy())
            d = max(int(settings.divisions), 1)
            best_x = np.clip([current[n] for n in names], lo, hi)
            best_f = target_function(_values(names, best_x, fixed), samples, stage)
            evaluations += 1
            for rnd in range(settings.rounds):
                prev = best_f
                job = _Round(names, lo, hi, fixed, stage, settings, starts)
                best_x, best_f, ev = job.run(pool, rng, best_x, best_f)
                evaluations += ev
                history.append(
                    {
                        "stage": stage,
                        "round": rnd,
                        "cube": [lo.round(4).tolist(), hi.round(4).tolist()],
                        "best": best_f,
                        "x": dict(zip(names, np.round(best_x, 4).tolist(), strict=True)),
                    }
                )
                done_rounds += 1
                if progress is not None:
                    progress(done_rounds / total_rounds, stage, rnd, best_f)
                if prev - best_f < settings.error_bound and rnd > 0:
                    break
                # the cube shrinks around the grid point nearest the best solution
                cell = (hi - lo) / d
                nearest = lo + np.round((best_x - lo) / cell) * cell
                lo = np.clip(nearest - cell, *outer)
                hi = np.clip(nearest + cell, *outer)
            current.update(_values(names, best_x, {}))
        final = target_function(current, samples)
        evaluations += 1
    finally:
        pool.close()
    return FitResult(current, final, start_target, evaluations, history)


def _init_pool_worker(parent: int, samples) -> None:
    """A local pool's worker: it ends with its parent, and holds the training samples."""
    exit_with_parent(parent)
    _init_worker(samples)


def load_quality(path) -> dict:
    """Quality values from a JSON file with a "quality" object (a fitted preset, a brush or
    paper preset, or a bare object of values); every value is checked."""
    d = read_json(path, "quality file", ParameterError, max_bytes=2**20)
    q = d.get("quality", d) if isinstance(d, dict) else None
    if not isinstance(q, dict):
        raise ParameterError(f"quality file {path}: needs a 'quality' object of parameter values")
    try:
        checked = QualityParams().with_values(q).to_dict()
    except ParameterError as exc:
        raise ParameterError(f"quality file {path}: {exc}") from None
    return {k: v for k, v in checked.items() if k in q}


def save_preset(result: FitResult, path, name: str | None = None) -> Path:
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    write_atomic(p, json.dumps(result.to_preset(name or p.stem), indent=2) + "\n")
    return p
