# SPDX-License-Identifier: GPL-3.0-or-later
"""Automatic imitation (Sec. 9): write a character from stroke data with the brush.

The medians are the brush's path; the outlines say how wide each stroke is at every point of its
median; the brush's own response - how wide a mark each press depth leaves, and how far behind
the brush's base the mark lies, with the current brush, paper, ink and quality parameters - is
measured by simulation (``calibrate``) and turns width into press (z) and into where the base
must go so that the ink lands on the median. A stroke is written as a calligrapher writes it:
the brush comes down onto the start, presses where the stroke is thick, travels, eases off
where it thins and lifts off the end, leaving the point; between strokes it travels in the air,
and it dips again before every stroke (or after every ``dip_every_mm`` of writing).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np

from ..core.params import HOVER_MM, MAX_PAPER_SIDE_PX, ParameterError, number_within, short_repr
from ..core.recording import PAPER_MM_RANGE, PX_PER_MM_RANGE, Dip, Recording, quantise
from ..engine.simulation import Simulation
from .hanzi import check_char
from .outline import EM, TOP, median_pieces, median_radii, rasterise

CAL_PPM = 5.0  # px/mm of the calibration strokes
CAL_LENGTH_MM = 45.0
ENTRY_SAMPLES = 8
EXIT_SAMPLES = 8
MAX_PASSES = 50
DEFAULT_PASSES = 4  # practice passes a stroke gets by default (issue 16: < 10 s at 512 px)
MIN_SHEET_PX = 8
# what the brush does at a sample of a plan (Plan.phase)
IN_THE_AIR, ENTERING, WRITING, LIFTING = 0, 1, 2, 3


@dataclass
class Response:
    """The brush's measured response: at base depth press_mm below touching height, a straight
    stroke at speed_mm_s leaves an ink band width_mm wide (coverage above half) whose marks lie
    lag_mm behind the base along the way of travel."""

    press_mm: np.ndarray
    width_mm: np.ndarray
    lag_mm: np.ndarray
    speed_mm_s: float

    @property
    def max_width_mm(self) -> float:
        return float(self.width_mm.max())

    def press_for(self, width_mm) -> np.ndarray:
        """Inverse response: the press that leaves a band ``width_mm`` wide (monotone envelope
        of the measured widths, linear in between, clamped to the measured range)."""
        w = np.maximum.accumulate(self.width_mm)
        keep = np.concatenate([[True], np.diff(w) > 1e-6])
        return np.interp(width_mm, w[keep], self.press_mm[keep])

    def lag_for(self, press_mm) -> np.ndarray:
        return np.interp(press_mm, self.press_mm, self.lag_mm)

    def to_dict(self) -> dict:
        return {
            "press_mm": self.press_mm.round(4).tolist(),
            "width_mm": self.width_mm.round(4).tolist(),
            "lag_mm": self.lag_mm.round(4).tolist(),
            "speed_mm_s": self.speed_mm_s,
        }


def _settings(template: Recording, **changes) -> Recording:
    """A recording with the template's brush, paper, ink, quality, rate and seed, no dips, and
    the given samples and paper."""
    kw = {
        "brush": dict(template.brush),
        "ink": dict(template.ink),
        "quality": dict(template.quality),
        "dips": [],
        "extra": {},
    }
    return replace(template, **{**kw, **changes})


_CACHE: dict = {}


def _cache_key(template: Recording, *args) -> str:
    """The calibration's settings (the resolved brush, paper, ink and quality, the rate, the
    seed, the calibration's own arguments) and the engine's source: a changed model never
    reads an old response."""
    import hashlib
    from pathlib import Path

    key = repr((template.resolve(), template.sample_rate_hz, template.seed, args))
    h = hashlib.sha256(key.encode())
    for f in sorted(Path(__file__).resolve().parents[1].rglob("*.py")):  # all of sim
        h.update(f.read_bytes())
    return h.hexdigest()[:32]


def _cache_file(key: str):
    from pathlib import Path

    root = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(root) / "hairy_brush" / f"response-{key}.json"


def calibrate(
    template: Recording, speed_mm_s: float = 60.0, presses: int = 11, ppm: float = CAL_PPM
) -> Response:
    """The brush's response (``_calibrate``), cached per settings in the process and on disk
    (``~/.cache/hairy_brush``; the key includes the engine's source, so a changed model is
    measured again). The simulation is deterministic, so a cached response is the same one."""
    import json

    key = _cache_key(template, speed_mm_s, presses, ppm)
    if key in _CACHE:
        return _CACHE[key]
    path = _cache_file(key)
    try:
        d = json.loads(path.read_text())
        resp = Response(*(np.array(d[k], dtype=float) for k in ("press", "width", "lag")), d["v"])
    except (OSError, ValueError, KeyError, TypeError):
        resp = _calibrate(template, speed_mm_s, presses, ppm)
        d = {k: getattr(resp, f"{k}_mm").tolist() for k in ("press", "width", "lag")}
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            tmp = path.with_suffix(f".{os.getpid()}.tmp")
            tmp.write_text(json.dumps({**d, "v": resp.speed_mm_s}))
            os.replace(tmp, path)
        except OSError:
            pass  # a read-only home: measure each time
    _CACHE[key] = resp
    return resp


CAL_DEPTHS = (0.04, 0.42)  # press range of the calibration, as shares of the hair length:
# deeper, the belly buckles and splits and the band's width no longer follows the press


def _straight_plan(lines, press, step_mm: float) -> Plan:
    """A plan of straight strokes (calibration): each line ((x0, y0), (x1, y1)) in mm written
    as the writer writes a stroke, its width taken as its press (it only sets the entry's
    length), travel in the air between, a dip before each."""
    tg, wd, tn, ph, strokes = [], [], [], [], []
    for k, ((x0, y0), (x1, y1)) in enumerate(lines):
        a, b = np.array([x0, y0], float), np.array([x1, y1], float)
        n = max(int(np.ceil(np.linalg.norm(b - a) / step_mm)), 2) + 1
        pts = a + np.linspace(0.0, 1.0, n)[:, None] * (b - a)
        tang = (b - a) / max(float(np.linalg.norm(b - a)), 1e-9)
        if k:
            _air(tg, wd, tn, ph, np.array(lines[k - 1][1], float), a, tang, step_mm)
        n0 = sum(len(t) for t in tg)
        tg += [np.tile(a, (ENTRY_SAMPLES, 1)), pts, np.tile(b, (EXIT_SAMPLES, 1))]
        m = n + ENTRY_SAMPLES + EXIT_SAMPLES
        wd.append(np.full(m, float(press[k])))
        tn.append(np.tile(tang, (m, 1)))
        ph += [
            np.full(ENTRY_SAMPLES, ENTERING),
            np.full(n, WRITING),
            np.full(EXIT_SAMPLES, LIFTING),
        ]
        strokes.append((n0, n0 + m))
    dips = [s for s, _ in strokes]
    return Plan(*(np.concatenate(v) for v in (tg, wd, tn, ph)), dips, strokes)


def _calibrate(template: Recording, speed_mm_s: float, presses: int, ppm: float) -> Response:
    """Measure the brush's response by simulation: one straight stroke per press depth, each
    after a fresh dip, on one sheet, written with the writer's own movement (``_fill``: the tip
    lands moving and the belly presses as it goes - a stationary press splays the hair and
    leaves a wider band than the writer ever gets); the width is read across the ink band in
    the stroke's steady middle, the lag between the base and the centroid of the current marks.
    The widths are made monotone (pool adjacent violators) and the lags a straight line in the
    press (least squares): single readings wander by a few tenths of a millimetre."""
    _, geometry, _, ink = template.resolve()
    hair = geometry.hair_length_mm
    depths = np.linspace(*CAL_DEPTHS, presses) * hair
    gap = 6.0 * geometry.belly_diameter_mm + 10.0
    step_mm = speed_mm_s / template.sample_rate_hz
    lines = [((20.0, gap * (k + 1)), (20.0 + CAL_LENGTH_MM, gap * (k + 1))) for k in range(presses)]
    pl = _straight_plan(lines, depths, step_mm)
    samples = np.zeros((len(pl.target), 6))
    samples[:, :2], samples[:, 2] = pl.target, hair + HOVER_MM
    flat = Response(depths, depths, np.zeros(presses), float(speed_mm_s))  # no lead yet
    for k, (a, b) in enumerate(pl.strokes):
        body = np.flatnonzero(pl.phase[a:b] == WRITING)
        brush = (hair + HOVER_MM, hair, step_mm)
        _fill(samples, pl, flat, (a, b), np.full(len(body), depths[k]), np.zeros(len(body)), brush)
    dips = [Dip(i, ink.depth, tuple(ink.color), ink.wetness) for i in pl.dips]
    rec = _settings(
        template,
        samples=quantise(samples),
        width_mm=CAL_LENGTH_MM + 40.0,
        height_mm=gap * (presses + 1),
        px_per_mm=ppm,
        dips=dips,
    )
    sim = Simulation(rec)
    band_of = np.full(len(samples), -1)
    for k, (a, b) in enumerate(pl.strokes):
        body = np.flatnonzero(pl.phase[a:b] == WRITING) + a
        band_of[body[len(body) // 4 : len(body) - len(body) // 4]] = k  # the steady middle
    lags = [[] for _ in depths]
    while not sim.done:
        i = sim.index
        sim.step()
        k = band_of[i]
        if k >= 0 and sim.last_marks:
            xs = [(mk.cols + mk.ix0 + 0.5) / ppm for mk in sim.last_marks if mk.rows.size]
            if xs:
                lags[k].append(float(sim.brush.B[0] - np.concatenate(xs).mean()))
    dark = _coverage(sim)  # (H, W) bottom row first
    x0, x1 = int((20 + 0.3 * CAL_LENGTH_MM) * ppm), int((20 + 0.7 * CAL_LENGTH_MM) * ppm)
    widths = []
    for (_, y), _ in lines:
        r0, r1 = int((y - gap / 2) * ppm), int((y + gap / 2) * ppm)
        widths.append(float(dark[r0:r1, x0:x1].sum(axis=0).mean()) / ppm)
    lag = np.array([np.median(v) if v else np.nan for v in lags])
    ok = np.isfinite(lag)
    fit = np.polyfit(depths[ok], lag[ok], 1) if ok.sum() >= 2 else np.zeros(2)
    return Response(depths, _monotone(np.array(widths)), np.polyval(fit, depths), speed_mm_s)


def _monotone(v) -> np.ndarray:
    """The non-decreasing sequence nearest ``v`` in least squares (pool adjacent violators)."""
    blocks = []  # [mean, count]
    for x in np.asarray(v, dtype=float):
        blocks.append([x, 1])
        while len(blocks) > 1 and blocks[-2][0] > blocks[-1][0]:
            (m1, n1), (m2, n2) = blocks.pop(-2), blocks.pop(-1)
            blocks.append([(m1 * n1 + m2 * n2) / (n1 + n2), n1 + n2])
    return np.concatenate([np.full(n, m) for m, n in blocks])


def _coverage(sim: Simulation, rows=slice(None), cols=slice(None)) -> np.ndarray:
    """Ink coverage above half at the given pixels (bottom-first rows; all by default): the
    pixel's ink density against the density of the ink the brush carries."""
    full = np.maximum(1.0 - np.asarray(sim.ink.color, dtype=np.float32), 1e-6)
    dens = np.clip(sim.paper.ink[rows, cols], 0.0, 1.0)
    return np.mean(dens / full, axis=-1) > 0.5


def auto_size_mm(char: dict, response: Response, fill: float = 1.2) -> float:
    """A character size at which the character's widest stroke (twice the largest distance
    from a median to its outline) needs ``fill`` of the widest band the brush leaves as the
    writer moves it (measured so since issue 16; larger characters match their outline better,
    smaller ones carry more of the brush's texture: 1 is the measured balance)."""
    widest = max(float(r.max()) for _, r in median_radii(char)) * 2.0  # data units
    return float(np.clip(fill * response.max_width_mm * EM / max(widest, 1e-6), 20.0, 2000.0))


def _smooth(v, k: int) -> np.ndarray:
    if k <= 1 or len(v) < 3:
        return np.asarray(v, dtype=float)
    w = np.ones(k) / k
    pad = np.pad(np.asarray(v, dtype=float), (k // 2, k - 1 - k // 2), mode="edge")
    return np.convolve(pad, w, mode="valid")


class Pass(NamedTuple):
    """One practice pass of a stroke: how far its ink is from the outline (lower is better),
    the press and sideways placement it was written with, and its number."""

    error: float
    press: np.ndarray
    side: np.ndarray
    number: int


@dataclass
class Plan:
    """Per sample of a character's writing: where the ink should land (paper mm), how wide the
    stroke is there, the way of travel, and what the brush does: IN_THE_AIR, ENTERING (coming
    down onto a stroke), WRITING, LIFTING (off the stroke's end). ``dips`` are the samples
    before which the brush dips again."""

    target: np.ndarray  # (N, 2)
    width: np.ndarray  # (N,)
    tangent: np.ndarray  # (N, 2)
    phase: np.ndarray  # (N,) int
    dips: list
    strokes: list  # (first, end) sample of every stroke: entry, writing, lift-off


def _timed(dense, width, step_mm: float, slow_corners: float):
    """Sample a densely resampled median (mm) at the brush's pace: step_mm per sample on the
    straight, slower where the stroke turns (down to (1 - slow_corners) of the pace at a right
    angle), as a calligrapher slows into a turn so that the hair can follow."""
    seg = np.linalg.norm(np.diff(dense, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    if s[-1] <= 0 or len(dense) < 3:
        return dense[:1], width[:1]
    heading = np.unwrap(np.arctan2(*np.gradient(dense, axis=0).T[::-1]))
    win = max(int(round(1.5 / max(s[1] - s[0], 1e-9))), 1)  # +-1.5 mm
    pad = np.pad(heading, win, mode="edge")
    turn = np.abs(pad[2 * win :] - pad[: -2 * win])
    pace = np.clip(1.0 - slow_corners * turn / (np.pi / 2), 1.0 - slow_corners, 1.0)
    t = np.concatenate([[0.0], np.cumsum(seg / (0.5 * (pace[1:] + pace[:-1])))])
    n = max(int(np.ceil(t[-1] / step_mm)), 1) + 1
    ts = np.linspace(0.0, t[-1], n)
    si = np.interp(ts, t, s)
    pts = np.stack([np.interp(si, s, dense[:, 0]), np.interp(si, s, dense[:, 1])], axis=1)
    return pts, np.interp(si, s, width)


def _air(tg, wd, tn, ph, a, b, tang, step_mm) -> None:
    """Travel in the air from ``a`` to ``b`` (mm)."""
    k = max(int(np.linalg.norm(b - a) / (2 * step_mm)), 4)
    t = np.linspace(0.0, 1.0, k)[:, None]
    tg.append(a * (1 - t) + b * t)
    wd.append(np.zeros(k))
    tn.append(np.tile(tang, (k, 1)))
    ph.append(np.full(k, IN_THE_AIR))


def plan(
    char: dict,
    size_mm: float,
    step_mm: float,
    dip_every_mm: float | None = None,
    origin=(0.0, 0.0),
    slow_corners: float = 0.7,
) -> Plan:
    """The path of the writing: each median resampled every step_mm with the outline's width,
    one movement per piece of the median between its sharp corners (``median_pieces``: a
    hook's foot, a 折), each with an entry and a lift, travel in the air between movements.
    Each movement is smoothed on its own, so that a corner stays a corner."""
    scale = size_mm / EM
    dip_every = 0.0 if dip_every_mm is None else dip_every_mm
    tg, wd, tn, ph, dips, strokes = [], [], [], [], [], []
    since_dip, prev = np.inf, None
    fine = max(step_mm / scale / 4.0, 0.25)
    k = max(int(round(3.0 / fine / scale)), 1)  # +-1.5 mm: the cut's jitter smoothed
    for pieces in median_pieces(char, step=fine):
        moves = []
        for pts_d, width_d in pieces:
            dense = np.stack(
                [origin[0] + pts_d[:, 0] * scale, origin[1] + (pts_d[:, 1] - (TOP - EM)) * scale],
                axis=1,
            )
            dense = np.stack([_smooth(dense[:, 0], k), _smooth(dense[:, 1], k)], axis=1)
            pts, width = _timed(dense, _smooth(width_d * scale, k), step_mm, slow_corners)
            tang = np.gradient(pts, axis=0) if len(pts) > 1 else np.array([[1.0, 0.0]])
            tang = np.stack([_smooth(tang[:, 0], 5), _smooth(tang[:, 1], 5)], axis=1)
            tang /= np.maximum(np.linalg.norm(tang, axis=1, keepdims=True), 1e-9)
            moves.append((pts, _smooth(width, 3), tang))
        if prev is not None:  # travel in the air to the next stroke
            _air(tg, wd, tn, ph, prev, moves[0][0][0], moves[0][2][0], step_mm)
        n = sum(len(a) for a in tg)
        stroke_len = step_mm * sum(len(m[0]) - 1 for m in moves)
        if since_dip + stroke_len > dip_every:
            dips.append(n)
            since_dip = 0.0
        since_dip += stroke_len
        for j, (p, w, t) in enumerate(moves):
            if j:  # a sharp turn: lift, turn the tip in the air, come down on the corner
                _air(tg, wd, tn, ph, moves[j - 1][0][-1], p[0], t[0], step_mm)
            tg += [np.tile(p[0], (ENTRY_SAMPLES, 1)), p, np.tile(p[-1], (EXIT_SAMPLES, 1))]
            wd += [np.full(ENTRY_SAMPLES, w[0]), w, np.full(EXIT_SAMPLES, w[-1])]
            tn += [np.tile(t[0], (ENTRY_SAMPLES, 1)), t, np.tile(t[-1], (EXIT_SAMPLES, 1))]
            ph += [
                np.full(ENTRY_SAMPLES, ENTERING),
                np.full(len(p), WRITING),
                np.full(EXIT_SAMPLES, LIFTING),
            ]
        strokes.append((n, sum(len(a) for a in tg)))
        prev = moves[-1][0][-1]
    return Plan(
        np.concatenate(tg),
        np.concatenate(wd),
        np.concatenate(tn),
        np.concatenate(ph),
        dips,
        strokes,
    )


def measure_band(sim: Simulation, points, tangents, reach_mm: float, before=None, laid=None):
    """Across the way of travel at each of ``points`` (mm): the width (mm) of the ink band
    (coverage above half) nearest the point, the offset (mm, along the left normal) of its
    centre from the point, and whether the reading is the brush's own there: ink that was on
    the paper before the brush came to the point - ``before(index, rows, cols)`` says where,
    per point - makes up less than a third of the band. The band is read on ``laid(index, rows,
    cols)`` when given (the ink once the point's movement had lifted off), else on the paper."""
    ppm = sim.paper.ppm
    normal = np.stack([-tangents[:, 1], tangents[:, 0]], axis=1)
    k = max(int(reach_mm * ppm), 1)
    off = np.arange(-k, k + 1) / ppm
    pts = points[:, None, :] + off[None, :, None] * normal[:, None, :]
    cols = np.clip((pts[..., 0] * ppm).astype(int), 0, sim.paper.W - 1)
    rows = np.clip((pts[..., 1] * ppm).astype(int), 0, sim.paper.H - 1)
    idx = np.arange(len(points))
    cov = laid(idx, rows, cols) if laid is not None else _coverage(sim, rows, cols)
    old = before(idx, rows, cols) if before is not None else np.zeros_like(cov)
    width = np.zeros(len(points))
    centre = np.zeros(len(points))
    valid = np.zeros(len(points), dtype=bool)
    for j in range(len(points)):
        c = cov[j]
        if not c.any():
            valid[j] = True  # no ink near: a real reading of width zero
            continue
        edges = np.diff(np.concatenate([[0], c.astype(np.int8), [0]]))
        starts, ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
        mid = (starts + ends - 1) / 2.0
        dist = np.where((starts <= k) & (k < ends), 0.0, np.abs(mid - k))
        r = int(np.argmin(dist))
        a, b = starts[r], ends[r]
        width[j] = (b - a) / ppm
        centre[j] = (mid[r] - k) / ppm
        valid[j] = np.count_nonzero(old[j, a:b]) < (b - a) / 3.0
    return width, centre, valid


def _lead_along(path, lag, stop: bool = False):
    """Where the brush's base must be so that the ink lands on ``path``: the hair trails the
    base along the way it came, so the base runs ahead of the mark by the lag *along the path*
    (round a curve, not off its tangent). The lead builds up over the first stretch of the
    stroke, as the hair bends over behind the base, and beyond the path's end the base goes on
    along the last direction."""
    seg = np.linalg.norm(np.diff(path, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    lead = np.asarray(lag, dtype=float) * np.clip(s / np.maximum(lag, 1e-6), 0.0, 1.0)
    q = s + lead
    if stop:  # into a corner: the base stops on the corner, the hair catches up beneath it
        q = np.minimum(q, s[-1])
    out = np.stack([np.interp(q, s, path[:, 0]), np.interp(q, s, path[:, 1])], axis=1)
    if len(path) > 1 and s[-1] > 0:
        end_dir = path[-1] - path[-2]
        end_dir = end_dir / max(float(np.linalg.norm(end_dir)), 1e-9)
        past = np.maximum(q - s[-1], 0.0)
        out += past[:, None] * end_dir[None, :]
    return out


ENTRY_TOUCH = 0.15  # share of the press the tip lands with; the belly presses as it goes
TURN_EASE = 0.8  # press taken off at a reversal (a hook), less at a milder turn


def _entry_ramp(path, width) -> np.ndarray:
    """The press as a share of the planned press along the start of a stroke: the tip lands
    (``ENTRY_TOUCH``) while the brush already moves along the stroke, and the belly presses
    over the first stroke width of the way (a smoothstep), as a calligrapher enters - not a
    stationary press, which splays the hair into a round blob."""
    seg = np.linalg.norm(np.diff(path, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    ramp = float(np.clip(0.5 * np.max(width[: max(len(width) // 3, 1)]), 0.5, 0.25 * s[-1]))
    t = np.clip(s / max(ramp, 1e-6), 0.0, 1.0)
    entry = ENTRY_TOUCH + (1.0 - ENTRY_TOUCH) * t * t * (3.0 - 2.0 * t)
    return entry * _turn_ease(path, s)


def _turn_ease(path, s) -> np.ndarray:
    """Less press where the stroke turns back on itself (a hook, the sharp turn of a 折): a
    calligrapher eases the belly off and turns on the tip there; pressed through a sharp turn
    the hair sweeps round and leaves a round blot. 1 on the straight, down to 1 - TURN_EASE at a
    reversal, over +-1.5 mm."""
    if len(path) < 3 or s[-1] <= 0:
        return np.ones(len(path))
    d = np.gradient(path, axis=0)
    heading = np.unwrap(np.arctan2(d[:, 1], d[:, 0]))
    win = max(int(round(1.5 / max(s[-1] / (len(s) - 1), 1e-9))), 1)
    pad = np.pad(heading, win, mode="edge")
    turn = np.abs(pad[2 * win :] - pad[: -2 * win])
    return 1.0 - TURN_EASE * np.clip((turn - 0.9) / 1.4, 0.0, 1.0)


def _enter_and_leave(samples, pl, body, hover, hair, step_mm, at_turn=(False, False)) -> None:
    """The brush comes down moving along the movement's first direction, the tip touching where
    the body begins, and lifts off moving on along the last direction (a flick, so that hooks
    and left-falling strokes end in a point, not a blot from a lift on the spot). ``at_turn``:
    the movement begins after / ends at a sharp corner (``median_pieces``), where the brush lifts
    and lands on the corner itself (a flick there overshoots the corner)."""
    a = body[0] - 1
    while a >= 0 and pl.phase[a] == ENTERING:
        a -= 1
    entry = np.arange(a + 1, body[0])
    t0 = pl.tangent[body[0]]
    f = np.arange(1, len(entry) + 1) / max(len(entry), 1)
    back = (len(entry) + 1 - np.arange(1, len(entry) + 1)) * 0.5 * step_mm
    if at_turn[0]:  # after a sharp turn the tip comes down on the corner, not before it
        back = back * 0.0
    samples[entry, :2] = samples[body[0], :2] - back[:, None] * t0
    z_touch = max(samples[body[0], 2], hair - 0.2)  # the tip reaches the paper at the start
    samples[entry, 2] = hover + (z_touch - hover) * f
    b = body[-1] + 1
    while b < len(pl.phase) and pl.phase[b] == LIFTING:
        b += 1
    lift = np.arange(body[-1] + 1, b)
    lift = np.flatnonzero(pl.phase[a:b] == LIFTING) + a
    t1 = pl.tangent[body[-1]]
    f = np.arange(1, len(lift) + 1) / max(len(lift), 1)
    flick = 0.0 if at_turn[1] else 0.5 * step_mm  # into a sharp turn: lift on the corner
    samples[lift, :2] = samples[body[-1], :2] + (f * len(lift) * flick)[:, None] * t1
    samples[lift, 2] = samples[body[-1], 2] + (hover - samples[body[-1], 2]) * np.sqrt(f)


def _movements(items, body=None) -> list[np.ndarray]:
    """``items`` cut where the body samples (``body``, or the items themselves) jump: one piece
    per movement of the stroke (the brush lifts between them)."""
    body = items if body is None else body
    return np.split(items, np.flatnonzero(np.diff(body) > 1) + 1)


def _fill(samples, pl: Plan, response: Response, span, press, side, brush) -> np.ndarray:
    """Samples a..b (``span``) of one stroke of plan ``pl``: for each of its movements, come
    down, write with the given press and sideways placement per body sample (the press eased at
    the entry and at sharp turns, the base leading the ink by the response's lag), lift off
    (``_enter_and_leave``). ``brush`` is (hover, hair length, step) in mm."""
    a, b = span
    hover, hair, step_mm = brush
    body = np.flatnonzero(pl.phase[a:b] == WRITING) + a
    normal = np.stack([-pl.tangent[:, 1], pl.tangent[:, 0]], axis=1)
    j0 = 0
    runs = _movements(body)
    for r, run in enumerate(runs):
        j1 = j0 + len(run)
        p = press[j0:j1] * _entry_ramp(pl.target[run], pl.width[run])
        samples[run, :2] = _lead_along(pl.target[run], response.lag_for(p), r < len(runs) - 1)
        samples[run, :2] += side[j0:j1, None] * normal[run]
        samples[run, 2] = hair - p
        _enter_and_leave(samples, pl, run, hover, hair, step_mm, (r > 0, r < len(runs) - 1))
        j0 = j1
    samples[a:b] = quantise(samples[a:b])  # as the saved recording will hold them
    return body


@dataclass
class _Window:
    rows: np.ndarray  # (h, w) paper rows (bottom first) of the window
    cols: np.ndarray
    inside: np.ndarray  # (h, w) the stroke's outline


def _stroke_masks(char: dict, H: int, W: int) -> list[_Window]:
    """Every stroke's filled outline on the paper grid (the sheet is the em box), as a window
    around it."""
    from .outline import fill, stroke_polygons, to_image

    out = []
    for polys in stroke_polygons(char):
        img = [to_image(p, H) for p in polys]  # top-first pixel coordinates, H x H em box
        m = fill(img, H)[::-1]  # bottom row first, as the paper
        ys, xs = np.nonzero(m)
        if ys.size == 0:
            ys, xs = np.array([0]), np.array([0])
        r0, r1 = max(ys.min() - 2, 0), min(ys.max() + 3, H)
        c0, c1 = max(xs.min() - 2, 0), min(xs.max() + 3, W)
        rr, cc = np.mgrid[r0:r1, c0:c1]
        out.append(_Window(rr, cc, m[r0:r1, c0:c1]))
    return out


RECORD_EVERY = 4  # samples between the coverage records of a practice pass
PRACTICE_GAIN = 0.45  # share of a pass's width error corrected for the next (measured best)
PRACTICE_SIDE_GAIN = 0.8  # share of the band's sideways offset corrected (issue 16: measured)


def _movement_ends(phase, body) -> np.ndarray:
    """For each body sample, the first sample after its movement has lifted off."""
    runs = _movements(body)
    ends = []
    for run in runs:
        e = run[-1] + 1
        while e < len(phase) and phase[e] == LIFTING:
            e += 1
        ends.append(np.full(len(run), e))
    return np.concatenate(ends)


def _practise(sim, a, b, body, want, step_mm, pl, reach):
    """Write samples a..b, keeping a record of the ink coverage around the stroke every few
    samples and as each movement lifts off; returns ``before(index, rows, cols)``, the coverage
    each body point had just before the brush's mark reached it, and ``laid(index, rows,
    cols)``, the coverage once the point's movement had lifted off. So a stroke crossing its
    own ink, as at a hook, reads only the band it is laying down, and the band at a 折's
    shoulder or a hook's foot is read before the next movement lays its ink across the cut."""
    ppm = sim.paper.ppm
    lo = pl.target[a:b].min(axis=0) - reach - 2.0
    hi = pl.target[a:b].max(axis=0) + reach + 2.0
    c0, r0 = max(int(lo[0] * ppm), 0), max(int(lo[1] * ppm), 0)
    c1, r1 = min(int(hi[0] * ppm) + 1, sim.paper.W), min(int(hi[1] * ppm) + 1, sim.paper.H)
    rr, cc = np.mgrid[r0:r1, c0:c1]
    times, records = [], []
    for i in range(a, b + 1):
        lifted = i > a and pl.phase[i - 1] == LIFTING and (i == b or pl.phase[i] != LIFTING)
        if (i - a) % RECORD_EVERY == 0 or lifted or i == b:
            times.append(i)
            records.append(_coverage(sim, rr, cc))
        if i < b:
            sim.step()
    times, records = np.array(times), np.stack(records)
    # the brush's mark reaches a point about half its width (plus a millimetre) ahead of time
    ahead = np.ceil((want / 2.0 + 1.0) / step_mm).astype(int) + 1
    which = np.clip(np.searchsorted(times, body - ahead, side="right") - 1, 0, len(times) - 1)
    done = np.searchsorted(times, np.minimum(_movement_ends(pl.phase, body), b))

    def at(record_of):
        def cover(idx, rows, cols):
            inside = (rows >= r0) & (rows < r1) & (cols >= c0) & (cols < c1)
            rr_ = np.clip(rows - r0, 0, r1 - r0 - 1)
            cc_ = np.clip(cols - c0, 0, c1 - c0 - 1)
            return inside & records[record_of[idx][:, None], rr_, cc_]

        return cover

    return at(which), at(done)


def _check_writing(n_px, size_mm, passes, dip_every_mm, px_per_mm) -> None:
    """The writer's arguments in range (the sheet's size and resolution are checked once the
    size is known)."""
    if isinstance(passes, bool) or not isinstance(passes, int) or not 1 <= passes <= MAX_PASSES:
        raise ParameterError(
            f"practice passes must be a whole number in [1, {MAX_PASSES}], got {short_repr(passes)}"
        )
    if px_per_mm is None and (
        isinstance(n_px, bool)
        or not isinstance(n_px, int)
        or not MIN_SHEET_PX <= n_px <= MAX_PAPER_SIDE_PX
    ):
        raise ParameterError(
            f"image size must be a whole number of pixels in [{MIN_SHEET_PX}, "
            f"{MAX_PAPER_SIDE_PX}], got {short_repr(n_px)}"
        )
    if px_per_mm is not None and not number_within(px_per_mm, *PX_PER_MM_RANGE):
        raise ParameterError(
            f"px_per_mm must be a number in [{PX_PER_MM_RANGE[0]:g}, {PX_PER_MM_RANGE[1]:g}], "
            f"got {short_repr(px_per_mm)}"
        )
    if size_mm is not None and not number_within(size_mm, *PAPER_MM_RANGE):
        raise ParameterError(
            f"character size must be a number of mm in [{PAPER_MM_RANGE[0]:g}, "
            f"{PAPER_MM_RANGE[1]:g}], got {short_repr(size_mm)}"
        )
    if dip_every_mm is not None and not number_within(dip_every_mm, 1e-3, 1e6):
        raise ParameterError(
            f"dip_every_mm must be a positive number, got {short_repr(dip_every_mm)}"
        )


def _check_sheet(size_mm: float, ppm: float) -> None:
    """The em box's sheet: a resolution and a pixel size a recording can hold."""
    lo, hi = PX_PER_MM_RANGE
    if not number_within(ppm, lo, hi):
        raise ParameterError(
            f"a {size_mm:.4g} mm character at this image size is {ppm:.4g} px/mm; the paper "
            f"takes {lo:g} to {hi:g} px/mm (change the size in mm or in pixels)"
        )
    if round(size_mm * ppm) > MAX_PAPER_SIDE_PX:
        raise ParameterError(
            f"a {size_mm:.4g} mm character at {ppm:.4g} px/mm is {round(size_mm * ppm)} px "
            f"wide; at most {MAX_PAPER_SIDE_PX} px"
        )


def _correct(response, press, side, want, got, centre, valid, ceiling):
    """The next pass's press and sideways placement: where the reading is this stroke's own,
    a share of the width error through the response's slope, and of the band's offset; smoothed
    along the stroke."""
    w_env = np.maximum.accumulate(response.width_mm)
    slope_tab = np.gradient(w_env, response.press_mm)
    p_max = float(response.press_mm[-1])
    mean_slope = 0.5 * (w_env[-1] - w_env[0]) / max(p_max - float(response.press_mm[0]), 1e-6)
    slope = np.maximum(np.interp(press, response.press_mm, slope_tab), mean_slope)
    dp = np.where(valid, PRACTICE_GAIN * (want - got) / slope, 0.0)
    dp = np.where(valid & (got == 0) & (want > 0), 0.5, dp)
    press = np.clip(press + _smooth(dp, 5), 0.0, ceiling)
    side = side - _smooth(np.where(valid & (got > 0), PRACTICE_SIDE_GAIN * centre, 0.0), 5)
    return press, side


CORNER_WIDTH = 0.9  # share of the widest band the brush is pressed for into a corner (measured:
# 0.8 is cleaner still but costs texture, 0.748 -> 0.73 on the bundled characters)


def _ceiling(pl: Plan, body, response: Response) -> np.ndarray:
    """The deepest press per body sample: the deepest measured, but into a sharp corner (the
    last stretch, as long as the movement is wide, of a movement ending at a 折's shoulder or a
    hook's foot) easing to the press that leaves ``CORNER_WIDTH`` of the widest band. The brush
    slows there and lifts on the spot, and a belly pressed to the calibration's limit splays
    and sweeps a grey, fibrous puff round the corner; a calligrapher presses into the turn
    firmly, not to the heel of the hair."""
    p_max = float(response.press_mm[-1])
    at_corner = float(response.press_for(CORNER_WIDTH * response.max_width_mm))
    top = np.full(len(body), p_max)
    runs = _movements(np.arange(len(body)), body)
    for run in runs[:-1]:  # every movement but the stroke's last ends at a corner
        path = pl.target[body[run]]
        seg = np.linalg.norm(np.diff(path, axis=0), axis=1)
        to_end = np.concatenate([np.cumsum(seg[::-1])[::-1], [0.0]])
        t = np.clip(1.0 - to_end / max(float(pl.width[body[run]].max()), 1e-6), 0.0, 1.0)
        top[run] = p_max - (p_max - at_corner) * t * t * (3.0 - 2.0 * t)
    return top


def _practise_stroke(sim, a, b, passes, fill, own, ctx) -> None:
    """Write samples a..b (one stroke) with ``fill(a, b, press, side)``; with passes > 1,
    practise it: write, read the band, correct, take it back (a snapshot), write again; the
    pass that best fills the stroke's own outline ``own`` stays."""
    pl, response, step_mm, reach = ctx
    body = np.flatnonzero(pl.phase[a:b] == WRITING) + a
    want = pl.width[body]
    ceiling = _ceiling(pl, body, response)
    press = np.minimum(response.press_for(want), ceiling)
    side = np.zeros(len(body))
    if passes == 1:
        fill(a, b, press, side)
        sim.run(until=b)
        return
    snap = sim.snapshot()
    inked_before = _coverage(sim, own.rows, own.cols)
    best = None
    for k in range(passes):
        if k:
            sim.restore(snap)
        fill(a, b, press, side)
        seen = _practise(sim, a, b, body, want, step_mm, pl, reach)
        got, centre, valid = measure_band(sim, pl.target[body], pl.tangent[body], reach, *seen)
        # the pass that best fills the stroke's own outline stays (new ink against it)
        new = _coverage(sim, own.rows, own.cols) & ~inked_before
        inter = np.count_nonzero(new & own.inside)
        err = -inter / max(np.count_nonzero(new | own.inside), 1)
        if best is None or err < best.error:
            best = Pass(err, press.copy(), side.copy(), k)
        if k == passes - 1:
            break
        press, side = _correct(response, press, side, want, got, centre, valid, ceiling)
    if best.number != k:  # the last pass was not the best: write the best again
        sim.restore(snap)
        fill(a, b, best.press, best.side)
        sim.run(until=b)


def write_character(
    char: dict,
    n_px: int,
    template: Recording,
    size_mm: float | None = None,
    response: Response | None = None,
    dip_every_mm: float | None = None,
    passes: int = DEFAULT_PASSES,
    progress=None,
    px_per_mm: float | None = None,
) -> tuple[Recording, Response, Simulation]:
    """Write ``char`` with the brush on an n_px x n_px sheet that is exactly the em box, with the
    template's brush, paper, ink, quality, rate and seed (``px_per_mm`` instead of n_px / size
    when a caller fixes the resolution). Returns the recording (it replays to the same image bit
    for bit), the response used and the finished simulation.

    The calibrated response gives each sample's press and the base's lead over the ink (feed
    forward). With ``passes`` > 1 the writer practises each stroke as a student of MiaoHong
    does (Sec. 7.2): it writes the stroke, reads the band it left across the median against the
    outline's width, corrects the press (through the response's slope) and the sideways
    placement, takes the stroke back (a snapshot) and writes it again; the best pass stays.

    Bad arguments raise ParameterError (CharacterError for bad character data) before any
    work."""
    check_char(char, "character data")
    _check_writing(n_px, size_mm, passes, dip_every_mm, px_per_mm)
    if size_mm is not None:  # the sheet can be checked before the brush is calibrated
        _check_sheet(float(size_mm), n_px / size_mm if px_per_mm is None else px_per_mm)
    if response is None:
        response = calibrate(template)
    size = auto_size_mm(char, response) if size_mm is None else float(size_mm)
    _, geometry, _, ink = template.resolve()
    hair = geometry.hair_length_mm
    step_mm = response.speed_mm_s / template.sample_rate_hz
    pl = plan(char, size, step_mm, dip_every_mm)
    N = len(pl.target)
    samples = np.zeros((N, 6))
    dips = [Dip(i, ink.depth, tuple(ink.color), ink.wetness) for i in pl.dips]
    ppm = n_px / size if px_per_mm is None else float(px_per_mm)
    _check_sheet(size, ppm)
    rec = _settings(
        template, samples=samples, width_mm=size, height_mm=size, px_per_mm=ppm, dips=dips
    )
    hover = hair + HOVER_MM
    samples[:, :2] = pl.target
    samples[:, 2] = hover
    samples[:] = quantise(samples)
    sim = Simulation(rec)
    reach = max(float(pl.width.max()), 1.0)
    masks = _stroke_masks(char, sim.paper.H, sim.paper.W) if passes > 1 else None

    def fill(a, b, press, side):
        return _fill(samples, pl, response, (a, b), press, side, (hover, hair, step_mm))

    for n_stroke, (a, b) in enumerate(pl.strokes):
        sim.run(until=a)  # travel in the air up to the stroke
        own = masks[n_stroke] if passes > 1 else None
        _practise_stroke(sim, a, b, passes, fill, own, (pl, response, step_mm, reach))
        if progress is not None:
            progress(b / N)
    sim.run()
    if progress is not None:
        progress(1.0)
    return rec, response, sim


def coverage_mask(sim: Simulation) -> np.ndarray:
    """Ink coverage above half, (H, W) bool, top row first."""
    return _coverage(sim)[::-1]


def font_mask(char: dict, n_px: int) -> np.ndarray:
    return rasterise(char, n_px)
