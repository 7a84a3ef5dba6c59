# SPDX-License-Identifier: GPL-3.0-or-later
"""Seeking a Simulation to any sample, forwards or backwards, in bounded time (scrubbing).

Snapshots are taken every ``every`` samples as the simulation passes them. Each stores the
brush, the random generator, the inertia predictor and only the paper tiles that changed since
the previous snapshot (the ink touches a small part of the paper), so many fit the memory
budget. Once they fill it, every other one is dropped and snapshots are taken half as often
from then on (``_thin``): a long recording keeps snapshots over its whole length in bounded
memory, twice as far apart each time the budget fills. A tile's content at snapshot k is its
newest stored copy at or before k (or the blank paper's). A seek restores the nearest snapshot
at or before the target - backwards or forwards - rewriting only the tiles that can differ,
then steps on in batches, as ``Simulation.run`` does.
Frame N is therefore exactly the image of simulating straight to N.
"""

from __future__ import annotations

import bisect
from dataclasses import dataclass, field

import numpy as np

from .simulation import Simulation

DEFAULT_BUDGET_BYTES = 256 * 2**20  # snapshots thin to stay under it (Timeline._thin)


@dataclass
class Snapshot:
    """The simulation at sample ``index``, its paper as the tiles changed since the previous
    snapshot (the rest is found in earlier snapshots)."""

    index: int
    brush: dict
    rng: dict
    predictor: object
    paper_step: int
    paper_stroke: object = None  # the stroke the paper was in (Paper.stroke), or None
    tiles: set = field(default_factory=set)
    nbytes: int = 0


class Timeline:
    def __init__(self, sim: Simulation, every: int = 4, budget_bytes: int = DEFAULT_BUDGET_BYTES):
        if sim.index != 0:
            raise ValueError("a timeline starts from a fresh simulation")
        self.sim = sim
        self.every = max(1, int(every))
        self.budget = int(budget_bytes)
        self.stride = 1  # snapshots are taken every ``every * stride`` samples (``_thin``)
        self.nbytes = 0
        self.snaps: dict[int, Snapshot] = {}
        self._history: dict[tuple[int, int], tuple[list, list]] = {}  # tile -> (indices, copies)
        # the last snapshot the simulation was exactly at, and the paper's version then
        self._base, self._base_version = 0, sim.paper.version
        self._take()

    # ------------------------------------------------------------------ snapshots
    def _take(self):
        sim, paper = self.sim, self.sim.paper
        sim._deposit_pending()
        i = sim.index
        snap = Snapshot(
            i,
            sim.brush.snapshot(),
            sim.rng.bit_generator.state,
            sim.predictor.state(),
            paper.step,
            paper.stroke,
        )
        for ty, tx in paper.tiles_since(self._base_version).tolist():
            content = paper.read_tile(ty, tx)
            self._remember((ty, tx), i, content)
            snap.tiles.add((ty, tx))
            snap.nbytes += sum(a.nbytes for a in content)
        snap.nbytes += sum(a.nbytes for a in snap.brush.values() if isinstance(a, np.ndarray))
        self.snaps[i] = snap
        self.nbytes += snap.nbytes
        self._base, self._base_version = i, paper.version

    def _remember(self, tile, index: int, content):
        """Keep a tile's content at snapshot ``index`` in its history (in index order)."""
        idx, copies = self._history.setdefault(tile, ([], []))
        at = bisect.bisect_left(idx, index)
        idx.insert(at, index)
        copies.insert(at, content)

    def _tile_at(self, tile, index: int):
        """A tile's content at snapshot ``index``: its newest copy at or before it."""
        idx, copies = self._history.get(tile, ((), ()))
        at = bisect.bisect_right(idx, index) - 1
        return copies[at] if at >= 0 else None

    def _restore(self, k: int):
        """Put the simulation at snapshot k, rewriting only the tiles that can differ."""
        sim, paper = self.sim, self.sim.paper
        sim._drop_pending()
        lo, hi = sorted((k, self._base))
        tiles = {tuple(t) for t in paper.tiles_since(self._base_version).tolist()}
        for j, snap in self.snaps.items():
            if lo < j <= hi:
                tiles |= snap.tiles
        for tile in tiles:
            paper.write_tile(*tile, self._tile_at(tile, k))
        snap = self.snaps[k]
        sim.index = k
        sim.brush.restore(snap.brush)
        sim.rng.bit_generator.state = snap.rng
        sim.predictor.set_state(snap.predictor)
        paper.step, paper.stroke = snap.paper_step, snap.paper_stroke
        self._base, self._base_version = k, paper.version

    # ------------------------------------------------------------------ seeking
    def seek(self, index: int, progress=None, should_stop=None) -> Simulation:
        """Move the simulation to ``index`` samples done. ``progress(fraction)`` is called now and
        then; ``should_stop()`` returning True ends the seek early (the simulation stays valid,
        at an earlier sample)."""
        sim = self.sim
        index = int(min(max(index, 0), len(sim.rec.samples)))
        best = max((k for k in self.snaps if k <= index), default=0)
        if index < sim.index or best > sim.index:
            self._restore(best)
        start, total = sim.index, max(index - sim.index, 1)
        while sim.index < index:
            nxt = min(index, (sim.index // self.every + 1) * self.every)
            sim.run(nxt)
            if sim.index % self.every == 0:
                self._at_boundary()
            if progress is not None:
                progress((sim.index - start) / total)
            if should_stop is not None and should_stop():
                break
        sim._deposit_pending()
        return sim

    def _at_boundary(self):
        i = self.sim.index
        if i in self.snaps:
            self._base, self._base_version = i, self.sim.paper.version
        elif i % (self.every * self.stride) == 0 and self.nbytes < self.budget:
            self._take()
            if self.nbytes >= self.budget:
                self._thin()  # once: if still full, the tiles alone fill it and snapshots stop

    def _thin(self) -> bool:
        """Over the budget: keep the snapshots on a grid twice as coarse (and the start, the
        newest and the one the simulation is at), drop the others, and take snapshots half as
        often from then on. A dropped snapshot's tiles pass to the next snapshot kept: a tile
        that changed again before it is forgotten (its newer copy is there), one that did not
        is now that snapshot's (the same content, unchanged since). Seeks stay exact: every
        snapshot kept is whole. Once a take (see _at_boundary): when the budget is still full
        after it, the tiles the ink touched fill it by themselves and snapshots stop there, as
        they did before thinning. Returns whether anything was dropped."""
        grid = 2 * self.every * self.stride
        keys = sorted(self.snaps)
        keep = {keys[0], keys[-1], self._base}
        drop = [k for k in keys if k % grid != 0 and k not in keep]
        if not drop:
            return False
        for k in drop:
            nxt = min(j for j in self.snaps if j > k)
            self._merge_into(self.snaps.pop(k), self.snaps[nxt])
        self.stride *= 2
        return True

    def _merge_into(self, snap: Snapshot, nxt: Snapshot):
        """Drop ``snap``, its tiles passed to ``nxt``, the snapshot after it (see _thin)."""
        self.nbytes -= snap.nbytes
        for tile in snap.tiles:
            idx, copies = self._history[tile]
            at = idx.index(snap.index)
            size = sum(a.nbytes for a in copies[at])
            if tile in nxt.tiles:  # changed again before nxt: its copy at nxt is the one kept
                del idx[at], copies[at]
            else:  # unchanged since: the same content is nxt's (no copy lies between them)
                idx[at] = nxt.index
                nxt.tiles.add(tile)
                nxt.nbytes += size
                self.nbytes += size

    def forget_after(self, index: int):
        """Drop the snapshots after ``index`` (the samples there changed)."""
        for k in [k for k in self.snaps if k > index]:
            snap = self.snaps.pop(k)
            self.nbytes -= snap.nbytes
            for tile in snap.tiles:
                idx, copies = self._history[tile]
                at = idx.index(k)
                del idx[at], copies[at]
        if self._base > index:
            best = max(k for k in self.snaps if k <= index)
            self._restore(best)
