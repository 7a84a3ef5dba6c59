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

from dataclasses import dataclass, replace

import numpy as np

from .engine import Simulation
from .hanzi import check_char
from .outline import EM, TOP, median_bands, median_radii, rasterise
from .params import HOVER_MM, MAX_PAPER_SIDE_PX, ParameterError, number_within, short_repr
from .recording import PAPER_MM_RANGE, PX_PER_MM_RANGE, Dip, Recording, quantise
from .strokes import stroke

CAL_PPM = 5.0  # px/mm of the calibration strokes
CAL_LENGTH_MM = 45.0
ENTRY_SAMPLES = 8
EXIT_SAMPLES = 8
MAX_PASSES = 50
MIN_SHEET_PX = 8


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


def calibrate(
    template: Recording, speed_mm_s: float = 60.0, presses: int = 7, ppm: float = CAL_PPM
) -> Response:
    """Measure the brush's response by simulation: one straight stroke per press depth, each
    after a fresh dip, on one sheet; the width is read across the ink band in the stroke's
    steady middle, the lag between the base and the centroid of the current marks."""
    _, geometry, _, ink = template.resolve()
    hair = geometry.hair_length_mm
    depths = np.linspace(0.04, 0.75, presses) * hair
    gap = 6.0 * geometry.belly_diameter_mm + 10.0
    width_mm = CAL_LENGTH_MM + 40.0
    height_mm = gap * (presses + 1)
    parts, dips, bands = [], [], []
    n = 0
    for k, p in enumerate(depths):
        y = gap * (k + 1)
        pts = [[20.0, y], [20.0 + CAL_LENGTH_MM, y]]
        s = stroke(
            pts,
            rate_hz=template.sample_rate_hz,
            speed_mm_s=speed_mm_s,
            press_mm=float(p),
            hair_length_mm=hair,
            hover_mm=HOVER_MM,
            lift_fraction=1e-6,
            entry_samples=ENTRY_SAMPLES,
            end_samples=EXIT_SAMPLES,
        )
        dips.append(Dip(n, ink.depth, tuple(ink.color), ink.wetness))
        bands.append((y, n + ENTRY_SAMPLES, n + len(s) - EXIT_SAMPLES))
        parts.append(s)
        n += len(s)
    rec = _settings(
        template,
        samples=np.concatenate(parts),
        width_mm=width_mm,
        height_mm=height_mm,
        px_per_mm=ppm,
        dips=dips,
    )
    sim = Simulation(rec)
    lags = [[] for _ in depths]
    band_of = np.full(n, -1)
    for k, (_, a, b) in enumerate(bands):
        lo, hi = a + (b - a) // 4, b - (b - a) // 4  # steady middle of the stroke
        band_of[lo:hi] = k
    while not sim.done:
        i = sim.index
        sim.step()
        k = band_of[i]
        if k >= 0 and sim.last_marks:
            xs = [(mk.cols + mk.ix0 + 0.5) / ppm for mk in sim.last_marks if mk.rows.size]
            if xs:
                lags[k].append(float(sim.brush.B[0] - np.concatenate(xs).mean()))
    dark = _coverage(sim)  # (H, W) bottom row first
    widths = []
    x0, x1 = int((20 + 0.3 * CAL_LENGTH_MM) * ppm), int((20 + 0.7 * CAL_LENGTH_MM) * ppm)
    for y, _, _ in bands:
        r0, r1 = int((y - gap / 2) * ppm), int((y + gap / 2) * ppm)
        widths.append(float(dark[r0:r1, x0:x1].sum(axis=0).mean()) / ppm)
    lag = np.array([np.median(v) if v else 0.0 for v in lags])
    return Response(depths, np.array(widths), lag, float(speed_mm_s))


def _coverage(sim: Simulation, rows=slice(None), cols=slice(None)) -> np.ndarray:
    """Ink coverage above half at the given pixels (bottom-first rows; all by default): the
    pixel's ink density against the density of the ink the brush carries."""
    full = np.maximum(1.0 - np.asarray(sim.ink.color, dtype=np.float32), 1e-6)
    dens = np.clip(sim.paper.ink[rows, cols], 0.0, 1.0)
    return np.mean(dens / full, axis=-1) > 0.5


def auto_size_mm(char: dict, response: Response, fill: float = 0.85) -> float:
    """A character size at which the character's widest stroke (twice the largest distance
    from a median to its outline) needs ``fill`` of the widest band the brush can leave."""
    widest = max(float(r.max()) for _, r in median_radii(char)) * 2.0  # data units
    return float(np.clip(fill * response.max_width_mm * EM / max(widest, 1e-6), 20.0, 2000.0))


def _smooth(v, k: int) -> np.ndarray:
    if k <= 1 or len(v) < 3:
        return np.asarray(v, dtype=float)
    w = np.ones(k) / k
    pad = np.pad(np.asarray(v, dtype=float), (k // 2, k - 1 - k // 2), mode="edge")
    return np.convolve(pad, w, mode="valid")


@dataclass
class Plan:
    """Per sample of a character's writing: where the ink should land (paper mm), how wide the
    stroke is there, the way of travel, and what the brush does: 0 = in the air, 1 = coming
    down onto a stroke, 2 = writing, 3 = lifting off. ``dips`` are the samples before which the
    brush dips again."""

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


def plan(
    char: dict,
    size_mm: float,
    step_mm: float,
    dip_every_mm: float | None = None,
    origin=(0.0, 0.0),
    slow_corners: float = 0.7,
) -> Plan:
    """The path of the writing: each median resampled every step_mm with the outline's width,
    entries and lifts on the spot, travel in the air between strokes."""
    scale = size_mm / EM
    dip_every = 0.0 if dip_every_mm is None else dip_every_mm
    tg, wd, tn, ph, dips, strokes = [], [], [], [], [], []
    since_dip, prev = np.inf, None
    fine = max(step_mm / scale / 4.0, 0.25)
    for pts_d, width_d in median_bands(char, step=fine):
        dense = np.stack(
            [origin[0] + pts_d[:, 0] * scale, origin[1] + (pts_d[:, 1] - (TOP - EM)) * scale],
            axis=1,
        )
        k = max(int(round(3.0 / fine / scale)), 1)  # +-1.5 mm: the cut's jitter smoothed
        dense = np.stack([_smooth(dense[:, 0], k), _smooth(dense[:, 1], k)], axis=1)
        pts, width = _timed(dense, _smooth(width_d * scale, k), step_mm, slow_corners)
        width = _smooth(width, 3)
        tang = np.gradient(pts, axis=0) if len(pts) > 1 else np.array([[1.0, 0.0]])
        tang = np.stack([_smooth(tang[:, 0], 5), _smooth(tang[:, 1], 5)], axis=1)
        tang /= np.maximum(np.linalg.norm(tang, axis=1, keepdims=True), 1e-9)
        if prev is not None:  # travel in the air to the next stroke
            k = max(int(np.linalg.norm(pts[0] - prev) / (2 * step_mm)), 4)
            t = np.linspace(0.0, 1.0, k)[:, None]
            tg.append(prev * (1 - t) + pts[0] * t)
            wd.append(np.zeros(k))
            tn.append(np.tile(tang[0], (k, 1)))
            ph.append(np.zeros(k, dtype=int))
        n = sum(len(a) for a in tg)
        stroke_len = step_mm * (len(pts) - 1)
        if since_dip + stroke_len > dip_every:
            dips.append(n)
            since_dip = 0.0
        since_dip += stroke_len
        tg += [np.tile(pts[0], (ENTRY_SAMPLES, 1)), pts, np.tile(pts[-1], (EXIT_SAMPLES, 1))]
        wd += [np.full(ENTRY_SAMPLES, width[0]), width, np.full(EXIT_SAMPLES, width[-1])]
        tn += [np.tile(tang[0], (ENTRY_SAMPLES, 1)), tang, np.tile(tang[-1], (EXIT_SAMPLES, 1))]
        ph += [np.full(ENTRY_SAMPLES, 1), np.full(len(pts), 2), np.full(EXIT_SAMPLES, 3)]
        strokes.append((n, n + ENTRY_SAMPLES + len(pts) + EXIT_SAMPLES))
        prev = pts[-1]
    return Plan(
        np.concatenate(tg),
        np.concatenate(wd),
        np.concatenate(tn),
        np.concatenate(ph),
        dips,
        strokes,
    )


def measure_band(sim: Simulation, points, tangents, reach_mm: float, before=None):
    """Across the way of travel at each of ``points`` (mm): the width (mm) of the ink band
    (coverage above half) nearest the point, the offset (mm, along the left normal) of its
    centre from the point, and whether the reading is the brush's own there: ink that was on
    the paper before the brush came to the point - ``before(index, rows, cols)`` says where,
    per point - makes up less than a third of the band."""
    ppm = sim.paper.ppm
    normal = np.stack([-tangents[:, 1], tangents[:, 0]], axis=1)
    k = max(int(reach_mm * ppm), 1)
    off = np.arange(-k, k + 1) / ppm
    pts = points[:, None, :] + off[None, :, None] * normal[:, None, :]
    cols = np.clip((pts[..., 0] * ppm).astype(int), 0, sim.paper.W - 1)
    rows = np.clip((pts[..., 1] * ppm).astype(int), 0, sim.paper.H - 1)
    cov = _coverage(sim, rows, cols)
    old = before(np.arange(len(points)), rows, cols) if before is not None else np.zeros_like(cov)
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


def _lead_along(path, lag):
    """Where the brush's base must be so that the ink lands on ``path``: the hair trails the
    base along the way it came, so the base runs ahead of the mark by the lag *along the path*
    (round a curve, not off its tangent). The lead builds up over the first stretch of the
    stroke, as the hair bends over behind the base, and beyond the path's end the base goes on
    along the last direction."""
    seg = np.linalg.norm(np.diff(path, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    lead = np.asarray(lag, dtype=float) * np.clip(s / np.maximum(lag, 1e-6), 0.0, 1.0)
    q = s + lead
    out = np.stack([np.interp(q, s, path[:, 0]), np.interp(q, s, path[:, 1])], axis=1)
    if len(path) > 1 and s[-1] > 0:
        end_dir = path[-1] - path[-2]
        end_dir = end_dir / max(float(np.linalg.norm(end_dir)), 1e-9)
        past = np.maximum(q - s[-1], 0.0)
        out += past[:, None] * end_dir[None, :]
    return out


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
PRACTICE_GAIN = 0.45  # share of a pass's measured error corrected for the next (measured best)


def _practise(sim, a, b, body, want, step_mm, pl, reach):
    """Write samples a..b, keeping a record of the ink coverage around the stroke every few
    samples; returns ``before(index, rows, cols)``: the coverage each body point had just
    before the brush's mark reached it (so that a stroke crossing its own ink, as at a hook,
    reads only the band it is laying down)."""
    ppm = sim.paper.ppm
    lo = pl.target[a:b].min(axis=0) - reach - 2.0
    hi = pl.target[a:b].max(axis=0) + reach + 2.0
    c0, r0 = max(int(lo[0] * ppm), 0), max(int(lo[1] * ppm), 0)
    c1, r1 = min(int(hi[0] * ppm) + 1, sim.paper.W), min(int(hi[1] * ppm) + 1, sim.paper.H)
    rr, cc = np.mgrid[r0:r1, c0:c1]
    times, records = [], []
    for i in range(a, b):
        if (i - a) % RECORD_EVERY == 0:
            times.append(i)
            records.append(_coverage(sim, rr, cc))
        sim.step()
    times, records = np.array(times), np.stack(records)
    # the brush's mark reaches a point about half its width (plus a millimetre) ahead of time
    ahead = np.ceil((want / 2.0 + 1.0) / step_mm).astype(int) + 1
    which = np.clip(np.searchsorted(times, body - ahead, side="right") - 1, 0, len(times) - 1)

    def before(idx, rows, cols):
        inside = (rows >= r0) & (rows < r1) & (cols >= c0) & (cols < c1)
        rr_ = np.clip(rows - r0, 0, r1 - r0 - 1)
        cc_ = np.clip(cols - c0, 0, c1 - c0 - 1)
        return inside & records[which[idx][:, None], rr_, cc_]

    return before


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


def write_character(
    char: dict,
    n_px: int,
    template: Recording,
    size_mm: float | None = None,
    response: Response | None = None,
    dip_every_mm: float | None = None,
    passes: int = 4,
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
    w_env = np.maximum.accumulate(response.width_mm)
    slope_tab = np.gradient(w_env, response.press_mm)
    p_max = float(response.press_mm[-1])
    mean_slope = 0.5 * (w_env[-1] - w_env[0]) / max(p_max - float(response.press_mm[0]), 1e-6)
    normal = np.stack([-pl.tangent[:, 1], pl.tangent[:, 0]], axis=1)
    samples[:, :2] = pl.target
    samples[:, 2] = hover
    samples[:] = quantise(samples)
    sim = Simulation(rec)
    reach = max(float(pl.width.max()), 1.0)
    masks = _stroke_masks(char, sim.paper.H, sim.paper.W) if passes > 1 else None

    def fill(a, b, press, side):
        """Samples a..b of one stroke: come down, write, lift off."""
        body = np.flatnonzero(pl.phase[a:b] == 2) + a
        samples[body, :2] = _lead_along(pl.target[body], response.lag_for(press))
        samples[body, :2] += side[:, None] * normal[body]
        samples[body, 2] = hair - press
        entry = np.flatnonzero(pl.phase[a:b] == 1) + a
        f = np.arange(1, len(entry) + 1) / max(len(entry), 1)
        samples[entry, :2] = samples[body[0], :2]
        samples[entry, 2] = hover + (samples[body[0], 2] - hover) * f
        lift = np.flatnonzero(pl.phase[a:b] == 3) + a
        f = np.arange(1, len(lift) + 1) / max(len(lift), 1)
        samples[lift, :2] = samples[body[-1], :2]
        samples[lift, 2] = samples[body[-1], 2] + (hover - samples[body[-1], 2]) * f
        samples[a:b] = quantise(samples[a:b])  # as the saved recording will hold them
        return body

    for n_stroke, (a, b) in enumerate(pl.strokes):
        sim.run(until=a)  # travel in the air up to the stroke
        body = np.flatnonzero(pl.phase[a:b] == 2) + a
        want = pl.width[body]
        press = response.press_for(want)
        side = np.zeros(len(body))
        snap = sim.snapshot() if passes > 1 else None
        if passes > 1:
            own = masks[n_stroke]
            inked_before = _coverage(sim, own.rows, own.cols)
        best = None
        for k in range(passes):
            if k:
                sim.restore(snap)
            fill(a, b, press, side)
            if passes == 1:
                sim.run(until=b)
                break
            before = _practise(sim, a, b, body, want, step_mm, pl, reach)
            got, centre, valid = measure_band(sim, pl.target[body], pl.tangent[body], reach, before)
            # the pass that best fills the stroke's own outline stays (new ink against it)
            new = _coverage(sim, own.rows, own.cols) & ~inked_before
            inter = np.count_nonzero(new & own.inside)
            err = -inter / max(np.count_nonzero(new | own.inside), 1)
            if best is None or err < best[0]:
                best = (err, press.copy(), side.copy(), k)
            if k == passes - 1:
                break
            # correct where the reading is this stroke's own; smooth along the stroke
            slope = np.maximum(np.interp(press, response.press_mm, slope_tab), mean_slope)
            dp = np.where(valid, PRACTICE_GAIN * (want - got) / slope, 0.0)
            dp = np.where(valid & (got == 0) & (want > 0), 0.5, dp)
            press = np.clip(press + _smooth(dp, 5), 0.0, p_max)
            side = side - _smooth(np.where(valid & (got > 0), PRACTICE_GAIN * centre, 0.0), 5)
        if passes > 1 and best[3] != k:  # the last pass was not the best: write the best again
            sim.restore(snap)
            fill(a, b, best[1], best[2])
            sim.run(until=b)
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
