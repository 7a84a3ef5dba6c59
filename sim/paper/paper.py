# SPDX-License-Identifier: GPL-3.0-or-later
"""The virtual paper psi (Sec. 6): per-pixel wetness and ink, absorption and drying (Eq. 24),
saturation spreading to the eight neighbours (Eq. 25) and colour with the stochastic dry-brush
weight (Eq. 26, 27; the draw of Eq. 27 is the brush's hair bundles', ``sim.brush.bristles``,
given with each mark as its ``skip``), and, beyond the paper, capillary wicking: below
saturation the sheet still draws liquid and pigment a little way out of a wet stroke along its
fibres (``_wick``: crisp but not ruled edges on sized xuan, a wider soft edge on raw xuan), and
the water halo: as the brush leaves the paper, the liquid the stroke left creeps on with the
finest pigment, a faint tint a millimetre or so round the ink (``_halo``, see HALO_MM); with it
the stroke's wet film levels (bundles' bands even out into solid ink where the hair left it
wet, ``lift.level_rows``, see LEVEL_MM) and a brush that leaves fast or lands loaded throws a
few droplets (``lift.spatter``, see SPATTER_EXIT). Ink laid over ink that has set adds a second
layer (Eq. 26 changed, see LAYER_S): a stroke crossing a dry one shows the crossing darker.

Buffers are float32, stored bottom row first (as Blender stores images). Ink is kept as density
(0 = the paper's own colour, as Eq. 7 takes colour code 0 for the paper); the visible colour is
paper_rgb * (1 - density). Wetness is in the brush's units (a fully loaded brush is about 1); the
paper's capacity is the upper bound of its wetness above which it saturates (Sec. 6, Eq. 25 with
the bound 1 read as the paper's capacity).

Drying is lazy and exact: every pixel remembers the step it was last brought up to date, and
when a step touches it again the missed drying is applied at once (drying is linear and clamped
at zero, so max(max(w - a, 0) - b, 0) = max(w - a - b, 0)). Work per step is bounded by the
marks' windows, never by the size of the paper.

The paper also remembers *where* it changed, so that whoever copies it (the image an artist sees,
snapshots for scrubbing, the taking-back of a cancelled stroke) works in proportion to what
changed: the sheet is cut into square tiles of TILE pixels, every change stamps its tiles with a
new ``version``, and ``tiles_since(v)`` lists the tiles changed after version v. A *hold* keeps
the content each tile had before its first change, so a stroke can be taken back exactly.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..core.frames import per_pixel
from ..image.png import to_uint8
from .grain import paper_grain  # noqa: F401 (the sheet's grain: read from here too)
from .laying import _RGB, FULL_WET, Laying, lay_out
from .lift import LEVEL_WET, box_mean, level_reach, level_rows, spatter
from .texture import paper_tone, sheet_draw, sheet_tone
from .wick import _wick, wick_steps

DRY_RATE = 1.0  # capacity units per second at dry = 1
TILE = 64  # pixels a side of the tiles by which changes are tracked


def _ring_sum(a):
    """Sum of the eight neighbours of every pixel of a (..., H, W), zero outside."""
    p = np.zeros(a.shape[:-2] + (a.shape[-2] + 2, a.shape[-1] + 2), dtype=a.dtype)
    p[..., 1:-1, 1:-1] = a
    rows = p[..., :-2] + p[..., 1:-1] + p[..., 2:]
    return rows[..., :-2, :] + rows[..., 1:-1, :] + rows[..., 2:, :] - a


class Paper:
    def __init__(
        self,
        width_px: int,
        height_px: int,
        px_per_mm: float,
        color=(1.0, 1.0, 1.0),
        capacity: float = 1.0,
        dry_per_step: float = 0.0,
        grain_seed: int = 0,
        fibre: float = 0.0,
        texture: float = 0.0,
    ):
        self.W, self.H = int(width_px), int(height_px)
        self.grain_seed = int(grain_seed)  # which sheet: the recording's seed (paper_grain)
        self.ppm = float(px_per_mm)
        self.color = np.asarray(color, dtype=np.float32)
        self.capacity = float(capacity)
        self.wet = np.zeros((self.H, self.W), dtype=np.float32)
        self.ink = np.zeros((self.H, self.W, 3), dtype=np.float32)
        self.last = np.zeros((self.H, self.W), dtype=np.int32)
        self.step = 0
        self.dry_per_step = float(dry_per_step)  # Eq. 24's "- dry", per sample
        self.texture = float(texture)  # how much the sheet's clouds and fibres show (paper_tone)
        self.fibre = float(fibre)  # how much the grain slows thin ink (paper_grain), 0: not
        # saturation spreads one pixel ring per pass: passes scale with resolution so that the
        # halo has the same size in millimetres at any px_per_mm
        self.sat_passes = max(1, int(round(self.ppm / 4.0)))
        self.wick_passes, self.wick_rate = wick_steps(self.capacity, self.ppm)
        self.wick_fibre = self.fibre  # how unevenly the sheet's fibres draw (_wick; 0: evenly)
        self.halo_px = halo_px(self.capacity, self.ppm)  # the water halo's reach (_halo; 0: none)
        self.stroke: WetStroke | None = None  # the stroke being written (for its halo)
        self.pigment = 1.0  # the ink's pigment per unit of liquid (see FULL_WET; 1: full)
        self.dt = 0.0  # seconds a step (the last deposit's: the droplets' speed, lift.spatter)
        self.brush_scale = 1.0  # the brush's size against its preset's (its droplets, spatter)
        self.version = 0  # bumped by every change; tile_ver holds each tile's last change
        self.tile_ver = np.zeros((-(-self.H // TILE), -(-self.W // TILE)), dtype=np.int64)
        self._holds = []

    # ------------------------------------------------------------------ where it changed
    def _touch(self, y0: int, y1: int, x0: int, x1: int):
        """Pixels [y0:y1, x0:x1] are about to change: holds save their tiles, versions move."""
        ty = slice(y0 // TILE, (y1 - 1) // TILE + 1)
        tx = slice(x0 // TILE, (x1 - 1) // TILE + 1)
        for hold in self._holds:
            hold.save(self, ty, tx)
        self.version += 1
        self.tile_ver[ty, tx] = self.version

    def tiles_since(self, version: int) -> np.ndarray:
        """(n, 2) tile indices (row, column) changed after ``version``."""
        return np.argwhere(self.tile_ver > version)

    def tile_box(self, ty: int, tx: int) -> tuple[slice, slice]:
        return slice(ty * TILE, min((ty + 1) * TILE, self.H)), slice(
            tx * TILE, min((tx + 1) * TILE, self.W)
        )

    def read_tile(self, ty: int, tx: int) -> tuple:
        """Copies of one tile's (ink, wet, last)."""
        ys, xs = self.tile_box(ty, tx)
        return self.ink[ys, xs].copy(), self.wet[ys, xs].copy(), self.last[ys, xs].copy()

    def write_tile(self, ty: int, tx: int, content):
        """Put a tile's (ink, wet, last) back (None: the blank paper's)."""
        ys, xs = self.tile_box(ty, tx)
        self._touch(ys.start, ys.stop, xs.start, xs.stop)
        if content is None:
            self.ink[ys, xs] = 0.0
            self.wet[ys, xs] = 0.0
            self.last[ys, xs] = 0
        else:
            self.ink[ys, xs], self.wet[ys, xs], self.last[ys, xs] = content

    def hold(self) -> PaperHold:
        """From now on keep every tile as it was before its first change (see give_back)."""
        h = PaperHold(self.step, self.stroke)
        self._holds.append(h)
        return h

    def give_back(self, hold: PaperHold):
        """Put the paper back exactly as it was at ``hold()``; the hold ends."""
        self.release(hold)
        for (ty, tx), content in hold.tiles.items():
            self.write_tile(ty, tx, content)
        self.step, self.stroke = hold.step, hold.stroke

    def release(self, hold: PaperHold):
        if hold in self._holds:
            self._holds.remove(hold)

    @property
    def shape(self):
        return (self.H, self.W)

    def deposit(self, marks, q, dt: float, step: int):
        """Apply this step's marks (one per touching primitive), Eq. 24-27. A mark's ``skip``
        (Eq. 27, drawn by the brush's hair bundles) marks the pixels that take no ink."""
        self.take(self.lay_out([marks])[0], q, dt, step)

    def lay_out(self, steps) -> list:
        """What the paper takes of each step's marks (``steps``: a list of steps' marks) that
        does not depend on the paper, for many steps at once (``sim.paper.laying``); ``take``
        puts each step's down, in order."""
        return lay_out(self, steps, GRAIN_DEPTH * self.fibre, FULL_WET / self.pigment)

    def take(self, laying: Laying | None, q, dt: float, step: int):
        """Put down one step's marks as ``lay_out`` laid them out (None: none touch the
        paper), Eq. 24-27."""
        self.step = step
        if laying is None:
            if self.stroke is not None:  # the brush has left the paper
                self._halo()
            return
        y0, y1, x0, x1 = laying.window
        self._touch(y0, y1, x0, x1)
        wet = self.wet[y0:y1, x0:x1]
        ink = self.ink[y0:y1, x0:x1]
        last = self.last[y0:y1, x0:x1]
        drystep = np.float32(self.dry_per_step)
        # lazy drying through the previous step; this step's "- dry" follows (Eq. 24)
        missed = np.maximum(step - 1 - last, 0).astype(np.float32)
        w = np.maximum(wet - drystep * missed, 0.0)
        if laying.follow is not None:
            self.dt = float(dt)
            self._follow(step, laying.window, *laying.follow)
        self._lay(w, laying, q, dt, missed)
        w = np.where(laying.dried.reshape(w.shape), w, np.maximum(w - drystep, 0.0))
        self._saturate_window(w, ink)
        if self.wick_passes:
            draw = sheet_draw(
                slice(y0, y1), slice(x0, x1), self.ppm, self.grain_seed, TILE, self.wick_fibre
            )
            _wick(w, ink, draw, self.wick_passes, self.wick_rate)
        wet[...] = w
        last[...] = step

    def _lay(self, w, laying: Laying, q, dt: float, missed):
        """Eq. 24 and 26-27 at the marks' pixels (``laying``) of the window whose wetness,
        dried through the previous step, is ``w`` (h, w), in place, and in the paper's ink; a
        pixel several marks cover takes them one after the other (Laying's rounds)."""
        loc, full, wet_tau, lay, bounds = laying[1:6]
        wf = w.reshape(-1)
        ab = np.float32(q.ab)
        lam = np.take(wf, loc)
        # Eq. 24: wet' = ab * wet_lambda + (1 - ab) * wet_tau - dry (once per step)
        new = ab * lam + (1 - ab) * wet_tau[: bounds[1]]
        new = np.maximum(new - np.float32(self.dry_per_step), 0.0)
        for k in range(1, len(bounds) - 1):  # later visits: the first pixels, each again
            head = new[: bounds[k + 1] - bounds[k]]
            np.maximum(ab * head + (1 - ab) * wet_tau[bounds[k] : bounds[k + 1]], 0.0, out=head)
        np.put(wf, loc, new)
        # Eq. 26-27 (model change, see FULL_WET): the pixel keeps the darker of the colour the
        # liquid offered can hold (lay_out) and what it had (pigment laid is not taken back)
        inkv = self.ink.reshape(-1).view(_RGB)  # one 12-byte element per pixel
        old = np.take(inkv, full).view(np.float32).reshape(-1, 3)
        # a second layer over ink that has set (see LAYER_S)
        after = LAYER_S / dt if dt > 0 else np.inf  # steps for the ink to set
        set_ = _set_share(lam, np.take(missed.reshape(-1), loc), after)
        top = np.maximum(old, lay)  # wet: the pigments mix, the darker shows
        stacked = old + lay * (1.0 - old)  # set: 1 - (1 - old)(1 - lay)
        np.maximum(old, top + per_pixel(stacked - top, set_), out=old)
        if laying.over is not None:  # the darkest of the later visits'
            head = old[: laying.over.shape[0]]
            np.maximum(head, laying.over, out=head)
        np.put(inkv, full, old.reshape(-1).view(_RGB))

    def _window(self, marks) -> tuple[int, int, int, int]:
        """(y0, y1, x0, x1): the marks' pixels and the reach of saturation around them."""
        margin = self.sat_passes + self.wick_passes + 1
        y0 = max(min(mk.iy0 for mk in marks) - margin, 0)
        x0 = max(min(mk.ix0 for mk in marks) - margin, 0)
        y1 = min(max(mk.iy0 + mk.shape[0] for mk in marks) + margin, self.H)
        x1 = min(max(mk.ix0 + mk.shape[1] for mk in marks) + margin, self.W)
        return y0, y1, x0, x1

    def _follow(self, step: int, window, darkest: tuple, here: tuple):
        """Keep the stroke being written in ``stroke``: where its windows lie, the step it
        began, the darkest colour its marks laid (the water halo's source, ``_halo``), and
        where the hair touched the paper first and in its last steps, with the liquid it
        offered there (``here``: the step's; the droplets it throws, ``lift.spatter``)."""
        y0, y1, x0, x1 = window
        t = self.stroke
        if t is None:
            self.stroke = WetStroke(step, y0, y1, x0, x1, darkest, here, (here,))
            return
        self.stroke = WetStroke(
            t.start,
            min(t.y0, y0),
            max(t.y1, y1),
            min(t.x0, x0),
            max(t.x1, x1),
            tuple(max(a, b) for a, b in zip(t.colour, darkest, strict=True)),
            t.land,
            (t.trail + (here,))[-TRAIL_STEPS:],
        )

    def _halo(self):
        """The water halo (see HALO_MM) of the stroke just written, as the brush leaves the
        paper: a bell of the wetness its pixels were left with, laid as a faint tint of its
        colour where that is darker than what a pixel holds. Only the tiles it darkens change;
        made HALO_ROWS rows at a time (a stroke across a large sheet needs no sheet-sized
        temporaries)."""
        t, self.stroke = self.stroke, None
        r = self.halo_px
        y0, y1 = max(t.y0 - 2 * r, 0), min(t.y1 + 2 * r, self.H)
        x0, x1 = max(t.x0 - 2 * r, 0), min(t.x1 + 2 * r, self.W)
        colour = np.asarray(t.colour, dtype=np.float32)
        outer = (y0, y1, x0, x1)
        bands = [(by0, min(by0 + HALO_ROWS, y1)) for by0 in range(y0, y1, HALO_ROWS)]
        # the wet film levels first: each band is read from the ink as the stroke left it (a
        # band's levelled ink is put down once no band still to be read reaches it)
        reach = level_reach(self)
        waiting = []
        for rows in bands:
            while waiting and waiting[0][0] <= rows[0] - reach:
                self._put(*waiting.pop(0)[1])
            levelled = level_rows(self, t.start, t.colour, rows, outer)
            if levelled is not None:
                waiting.append((rows[1], levelled))
        for _, levelled in waiting:
            self._put(*levelled)
        for rows in bands:
            self._halo_rows(t.start, colour, rows, outer)
        spatter(self, t, colour)

    def _put(self, at, values):
        """Put ``values`` (n, 3) into the ink at the pixels ``at`` (rows, columns)."""
        self._touch(int(at[0].min()), int(at[0].max()) + 1, int(at[1].min()), int(at[1].max()) + 1)
        self.ink[at] = values

    def _halo_rows(self, start: int, colour, rows, outer):
        """The halo at the rows ``rows`` (by0, by1) of the window ``outer``: the bell read from
        the stroke's wetness up to its reach (2 halo_px) above and below them."""
        (by0, by1), (y0, y1, x0, x1), r = rows, outer, self.halo_px
        sy0, sy1 = max(by0 - 2 * r, y0), min(by1 + 2 * r, y1)
        last = self.last[sy0:sy1, x0:x1]
        left = np.where(last >= start, self.wet[sy0:sy1, x0:x1], np.float32(0.0))
        if not left.any():
            return
        bell = box_mean(box_mean(box_mean(box_mean(left, r, 0), r, 1), r, 0), r, 1)
        reach = bell[by0 - sy0 : by1 - sy0]
        draw = sheet_draw(
            slice(by0, by1), slice(x0, x1), self.ppm, self.grain_seed, TILE, self.wick_fibre
        )
        faint = HALO_PIGMENT * np.minimum(reach * np.float32(1.0 / FULL_WET), 1.0) * draw
        tint = np.empty(faint.shape + (3,), dtype=np.float32)  # faint times the colour, ...
        for c in range(3):  # ... a colour at a time (long runs of numbers; issue 28)
            np.multiply(faint, colour[c], out=tint[..., c])
        ink = self.ink[by0:by1, x0:x1]
        over = [tint[..., c] > ink[..., c] for c in range(3)]
        darker = np.nonzero(over[0] | over[1] | over[2])
        if darker[0].size == 0:
            return
        ry0, ry1 = int(darker[0].min()), int(darker[0].max()) + 1
        rx0, rx1 = int(darker[1].min()), int(darker[1].max()) + 1
        self._touch(by0 + ry0, by0 + ry1, x0 + rx0, x0 + rx1)
        np.maximum(ink, tint, out=ink)

    def _saturate_window(self, w, ink):
        """Eq. 25, a pass per pixel ring of spread, over the neighbourhood of saturated pixels
        only (nothing else can change)."""
        for _ in range(self.sat_passes):
            over = np.nonzero(w > self.capacity)
            if over[0].size == 0:
                break
            sy0, sy1 = max(over[0].min() - 1, 0), over[0].max() + 2
            sx0, sx1 = max(over[1].min() - 1, 0), over[1].max() + 2
            self._saturate(w[sy0:sy1, sx0:sx1], ink[sy0:sy1, sx0:sx1], self.capacity)

    @staticmethod
    def _saturate(w, ink, cap: float):
        """Eq. 25: a pixel wetter than the paper's bound gives its excess to its unsaturated
        neighbours, each in proportion to how unsaturated it is. The ink goes with the water:
        a neighbour's ink moves toward the giver's by the share of a full load it receives.

        Every sum over the eight neighbours is a 3 x 3 box sum less the centre, done as two
        passes of three shifted adds (the ink a channel plane at a time)."""
        excess = np.maximum(w - cap, 0.0)
        if not np.any(excess > 0):
            return
        unsat = np.maximum(cap - w, 0.0)
        rho = _ring_sum(unsat)
        gave = rho > 0
        give = np.where(gave, excess / np.where(gave, rho, 1.0), 0.0)  # per unit unsat
        inflow = unsat * _ring_sum(give)
        planes = np.moveaxis(ink, -1, 0)  # (3, H, W) view of the ink
        pigment = unsat * _ring_sum(give * planes)
        w -= np.where(gave, excess, 0.0)
        w += inflow
        got = inflow > 0
        mix = pigment / np.where(got, inflow, 1.0)
        share = np.minimum(inflow, 1.0)
        planes += np.where(got, (mix - planes) * share, 0.0)

    def wetness(self) -> np.ndarray:
        """Current wetness of every pixel, drying applied up to the current step."""
        missed = np.maximum(self.step - self.last, 0).astype(np.float32)
        return np.maximum(self.wet - np.float32(self.dry_per_step) * missed, 0.0)

    def rgb(self) -> np.ndarray:
        """Visible colour (H, W, 3) float32 in [0, 1], bottom row first."""
        return self.visible(self.ink, slice(0, self.H), slice(0, self.W))

    def visible(self, ink, rows: slice, cols: slice) -> np.ndarray:
        """The colour seen at the pixels (``rows``, ``cols``: paper indices, bottom row first)
        holding ``ink`` ((h, w, 3), or one ink for all of them): the sheet's colour, with its
        clouds and fibres (``paper_tone``), under the ink."""
        ink = np.broadcast_to(ink, (rows.stop - rows.start, cols.stop - cols.start, 3))
        under = 1.0 - np.clip(ink, 0.0, 1.0)
        if self.texture <= 0.0:
            return self.color * under
        return self.sheet(rows, cols) * under

    def sheet(self, rows: slice, cols: slice, ppm: float | None = None) -> np.ndarray:
        """The bare sheet's colour (h, w, 3) at the pixels (``rows``, ``cols``) of a grid of
        ``ppm`` pixels a millimetre (the paper's own by default; a print's finer one keeps the
        clouds and fibres their size in mm): its colour times its tone (``paper_tone``)."""
        if ppm is None:  # the paper's own pixels: made a tile at a time, once (sheet_tone)
            tone = sheet_tone(rows, cols, self.ppm, self.texture, self.grain_seed, TILE)
        else:
            tone = paper_tone(rows, cols, float(ppm), self.texture, self.grain_seed)
        return np.clip(self.color * tone[..., None], 0.0, 1.0)

    def rgb8(self, chunk_rows: int = 256) -> np.ndarray:
        """Visible colour as (H, W, 3) uint8, TOP row first (an image file's order), made a band
        of rows at a time so that a 4K paper needs no full-size float temporaries."""
        out = np.empty((self.H, self.W, 3), dtype=np.uint8)
        for y0 in range(0, self.H, chunk_rows):
            y1 = min(y0 + chunk_rows, self.H)
            rows = slice(self.H - y1, self.H - y0)
            out[y0:y1] = to_uint8(self.visible(self.ink[rows], rows, slice(0, self.W))[::-1])
        return out

    def snapshot(self) -> dict:
        return {
            "wet": self.wet.copy(),
            "ink": self.ink.copy(),
            "last": self.last.copy(),
            "step": self.step,
            "stroke": self.stroke,
        }

    def restore(self, snap: dict):
        self._touch(0, self.H, 0, self.W)
        self.wet[...] = snap["wet"]
        self.ink[...] = snap["ink"]
        self.last[...] = snap["last"]
        self.step = snap["step"]
        self.stroke = snap.get("stroke")


GRAIN_DEPTH = 0.25  # the grain changes the offer a pixel takes by up to +- GRAIN_DEPTH fibre / 2


class WetStroke(NamedTuple):
    """The stroke being written (``Paper.stroke``): the step its first mark was laid, the
    union of its windows (paper pixels, y0:y1, x0:x1), the darkest ink colour it laid, where
    its first marks lay (row, column: their middle in paper pixels; the mean liquid the hair
    offered; the radius of a disc of the marks' area, px) and the same of its last TRAIL_STEPS
    steps (the droplets it throws, lift.spatter)."""

    start: int
    y0: int
    y1: int
    x0: int
    x1: int
    colour: tuple
    land: tuple = ()
    trail: tuple = ()


TRAIL_STEPS = 4


# Model addition (not in the paper): the water halo. Beyond the fringe the wick pulls, the
# liquid a stroke leaves creeps on into the sheet while it dries and carries the finest of the
# pigment with it: a faint grey aura a millimetre or so round the ink, as scans of real writing
# show (a quarter of a stroke's width out, at a few per cent of its density). It is laid once
# a stroke, as the brush leaves the paper (``Paper._halo``): its reach is the solution of that
# slow spreading, a bell of HALO_MM / capacity mm (two box filters a side, each that wide) of
# the wetness the stroke left in its pixels, and a pixel takes HALO_PIGMENT of the stroke's
# colour where that reach brings a full load (FULL_WET), less in proportion, times how well it
# draws (``sheet_draw``), keeping the darker of that and what it had: never darker than a
# faint tint, never darkening the stroke itself. Smooth paper (capacity small) and a mesh's
# texels (``Simulation`` sets halo_px 0: a texel's neighbours are not the sheet's) have none.
HALO_MM = 1.3
HALO_PIGMENT = 0.14
HALO_MAX_PX = 16
HALO_ROWS = 256  # rows of the sheet the halo is made at a time (its memory: see Paper._halo)


# Model change to Eq. 26 (not in the paper): a second layer. Where the hair lays ink over ink
# that has set (Eq. 24's wetness there gone below LEVEL_WET: the sheet has taken the liquid and
# its pigment lies fixed in the fibres) and that no mark has come near for LAYER_S seconds (an
# earlier stroke, or a return over the same ground after a pause), the new pigment lies over
# the old one: the densities combine as layers do (Beer-Lambert, the pigments add: 1 - (1 -
# old)(1 - new)), so a stroke crossing a dry one shows the crossing darker, most of all in
# pale or depleted ink. Over ink still wet, or within the pass that laid it, the pixel keeps
# the darker of the two as before (FULL_WET: the liquid's pigment mixes, a pixel under the
# hair for many steps is not blackened by them); between, in proportion to how far it has set.
LAYER_S = 0.25


def _set_share(wet, missed, steps: float) -> np.ndarray:
    """How far the ink of pixels of wetness ``wet`` (dried through the last step) that no mark
    window has touched for ``missed`` steps has set (0: wet or recent, 1: set), float32."""
    dry = np.clip(1.0 - wet * np.float32(1.0 / LEVEL_WET), 0.0, 1.0)
    return np.where(missed >= steps, dry, np.float32(0.0)).astype(np.float32)


def halo_px(capacity: float, ppm: float) -> int:
    """Half-width (px) of each box filter of the water halo (0: none)."""
    return int(min(round(HALO_MM / max(capacity, 1e-9) * ppm), HALO_MAX_PX))


class PaperHold:
    """The tiles of a Paper as they were before their first change since ``Paper.hold()``."""

    def __init__(self, step: int, stroke: WetStroke | None = None):
        self.step = step
        self.stroke = stroke
        self.tiles: dict[tuple[int, int], tuple] = {}
        self.nbytes = 0

    def save(self, paper: Paper, ty: slice, tx: slice):
        for y in range(ty.start, ty.stop):
            for x in range(tx.start, tx.stop):
                if (y, x) not in self.tiles:
                    content = paper.read_tile(y, x)
                    self.tiles[(y, x)] = content
                    self.nbytes += sum(a.nbytes for a in content)
