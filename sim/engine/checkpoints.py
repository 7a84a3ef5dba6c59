# SPDX-License-Identifier: GPL-3.0-or-later
"""A timeline's snapshots on disk (a farm's or a bake's checkpoints): one compressed file a
snapshot with the tiles that changed since the previous one, and a manifest naming the key
they were simulated from (``cache_key_of`` reads it back, None when it is not usable)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from .timeline import Snapshot, Timeline

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
