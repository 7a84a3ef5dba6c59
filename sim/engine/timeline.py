# SPDX-License-Identifier: GPL-3.0-or-later
"""Seeking a Simulation to any sample, forwards or backwards, in bounded time (scrubbing).

Snapshots are taken every ``every`` samples as the simulation passes them. Each stores the
brush, the random generator, the inertia predictor and only the paper tiles that changed since
the previous snapshot (the ink touches a small part of the paper), so many fit the memory
budget. A tile's content at snapshot k is its newest stored copy at or before k (or the blank
paper's). A seek restores the nearest snapshot at or before the target - backwards or forwards -
rewriting only the tiles that can differ, then steps on in batches, as ``Simulation.run`` does.
Frame N is therefore exactly the image of simulating straight to N.
"""

from __future__ import annotations

import bisect
import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .simulation import Simulation

DEFAULT_BUDGET_BYTES = 768 * 2**20


@dataclass
class Snapshot:
    """The simulation at sample ``index``, its paper as the tiles changed since the previous
    snapshot (the rest is found in earlier snapshots)."""

    index: int
    brush: dict
    rng: dict
    predictor: object
    paper_step: int
    tiles: set = field(default_factory=set)
    nbytes: int = 0


class Timeline:
    def __init__(self, sim: Simulation, every: int = 4, budget_bytes: int = DEFAULT_BUDGET_BYTES):
        if sim.index != 0:
            raise ValueError("a timeline starts from a fresh simulation")
        self.sim = sim
        self.every = max(1, int(every))
        self.budget = int(budget_bytes)
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
            i, sim.brush.snapshot(), sim.rng.bit_generator.state, sim.predictor.state(), paper.step
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
        sim._pending = []
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
        paper.step = snap.paper_step
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
        elif self.nbytes < self.budget:
            self._take()

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


# ------------------------------------------------------------------------------ on disk
CACHE_FORMAT = "hairy-brush-checkpoints"
CACHE_VERSION = 1


def save_checkpoints(timeline: Timeline, folder, key: str):
    """Write the timeline's snapshots to ``folder``: one file a snapshot holding the tiles that
    changed since the previous one (compressed), and a manifest naming ``key`` (what the
    checkpoints were simulated from). Files of snapshots no longer kept are removed."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    names = []
    for index in sorted(timeline.snaps):
        snap = timeline.snaps[index]
        tiles = sorted(snap.tiles)
        arrays = {f"brush_{k}": v for k, v in snap.brush.items() if isinstance(v, np.ndarray)}
        hist, vel = snap.predictor
        arrays["predictor_history"] = np.array(hist, dtype=float).reshape(len(hist), 6)
        arrays["predictor_velocity"] = np.asarray(vel, dtype=float)
        arrays["tiles"] = np.array(tiles, dtype=np.int64).reshape(-1, 2)
        for j, tile in enumerate(tiles):
            ink, wet, last = timeline._tile_at(tile, index)
            arrays[f"ink_{j}"], arrays[f"wet_{j}"], arrays[f"last_{j}"] = ink, wet, last
        meta = {
            "index": index,
            "paper_step": snap.paper_step,
            "rng": snap.rng,
            "brush": {k: v for k, v in snap.brush.items() if not isinstance(v, np.ndarray)},
        }
        arrays["meta"] = np.frombuffer(json.dumps(meta).encode("utf-8"), dtype=np.uint8)
        name = f"checkpoint_{index:08d}.npz"
        np.savez_compressed(folder / name, **arrays)
        names.append(name)
    for old in folder.glob("checkpoint_*.npz"):
        if old.name not in names:
            old.unlink()
    manifest = {"format": CACHE_FORMAT, "version": CACHE_VERSION, "key": key, "files": names}
    (folder / "manifest.json").write_text(json.dumps(manifest), encoding="utf-8")


def cache_key_of(folder) -> str | None:
    """The key the checkpoints in ``folder`` were made for (None: no usable cache there)."""
    try:
        m = json.loads((Path(folder) / "manifest.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    ok = isinstance(m, dict) and m.get("format") == CACHE_FORMAT
    return m.get("key") if ok and m.get("version") == CACHE_VERSION else None


def load_checkpoints(timeline: Timeline, folder):
    """Give a fresh timeline the snapshots saved in ``folder`` (see save_checkpoints)."""
    m = json.loads((Path(folder) / "manifest.json").read_text(encoding="utf-8"))
    for name in m["files"]:
        with np.load(Path(folder) / name) as z:
            meta = json.loads(bytes(z["meta"]).decode("utf-8"))
            index = int(meta["index"])
            if index in timeline.snaps:
                continue
            brush = dict(meta["brush"])
            brush.update({k[6:]: z[k] for k in z.files if k.startswith("brush_")})
            hist = [row for row in z["predictor_history"]]
            snap = Snapshot(
                index, brush, meta["rng"], (hist, z["predictor_velocity"]), meta["paper_step"]
            )
            for j, (ty, tx) in enumerate(z["tiles"].tolist()):
                content = (z[f"ink_{j}"], z[f"wet_{j}"], z[f"last_{j}"])
                timeline._remember((ty, tx), index, content)
                snap.tiles.add((ty, tx))
                snap.nbytes += sum(a.nbytes for a in content)
        timeline.snaps[index] = snap
        timeline.nbytes += snap.nbytes
