# SPDX-License-Identifier: GPL-3.0-or-later
"""A timeline's snapshots on disk (a farm's or a bake's checkpoints): one compressed file a
snapshot with the tiles that changed since the previous one, and a manifest.

A cache is either provably the one asked for or not used at all (issue 30):

- every file carries the key it was simulated for (what the caller says identifies the
  recording and its settings), the manifest lists every file with its size, and loading checks
  all of it - the manifest's key, each file's size, key, index and arrays (the zip's CRCs
  catch damaged bytes) - before the timeline gets anything; any doubt is a ``CacheError``,
  and the caller simulates from the start;
- a new cache is written into a fresh folder beside the old one and swapped in whole at the
  end, so a failure while saving (a full disk, a kill) leaves the previous cache as it was, or
  no cache at all - never files of two bakes under one manifest."""

from __future__ import annotations

import contextlib
import json
import os
import re
import secrets
import shutil
import time
from pathlib import Path

import numpy as np

from ..core.files import write_atomic, write_json_atomic
from ..paper.paper import WetStroke
from .timeline import Snapshot, Timeline

CACHE_FORMAT = "hairy-brush-checkpoints"
CACHE_VERSION = 4  # 2: the key in every file, the files' sizes in the manifest; 3: the stroke;
# 4: the stroke's landing and last steps (the droplets it throws, sim.paper.lift.spatter)
MANIFEST = "manifest.json"
CHECKPOINT = re.compile(r"checkpoint_(\d{8})\.npz")
LEFTOVER_AGE_S = 3600.0  # a half-written cache folder older than this is an interrupted save's


class CacheError(ValueError):
    """A cache folder is not provably the one asked for (stale, damaged or incomplete)."""


# ------------------------------------------------------------------------------ saving
def save_checkpoints(timeline: Timeline, folder, key: str) -> None:
    """Write the timeline's snapshots as the cache in ``folder`` for ``key``: into a new folder
    beside it, swapped in whole once every file and the manifest are on disk."""
    folder = Path(folder)
    folder.parent.mkdir(parents=True, exist_ok=True)
    _remove_leftovers(folder)
    new = folder.parent / f".{folder.name}.new-{os.getpid()}-{secrets.token_hex(4)}"
    new.mkdir()
    try:
        files = [_save_snapshot(timeline, index, new, key) for index in sorted(timeline.snaps)]
        manifest = {"format": CACHE_FORMAT, "version": CACHE_VERSION, "key": key, "files": files}
        write_json_atomic(new / MANIFEST, manifest)
        _swap_in(new, folder)
    except BaseException:
        shutil.rmtree(new, ignore_errors=True)
        raise


def _save_snapshot(timeline: Timeline, index: int, folder: Path, key: str) -> dict:
    """One snapshot's file: its brush, predictor, generator and changed tiles, and the key."""
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
        "format": CACHE_FORMAT,
        "version": CACHE_VERSION,
        "key": key,
        "index": index,
        "paper_step": snap.paper_step,
        "paper_stroke": snap.paper_stroke,
        "rng": snap.rng,
        "brush": {k: v for k, v in snap.brush.items() if not isinstance(v, np.ndarray)},
    }
    arrays["meta"] = np.frombuffer(json.dumps(meta).encode("utf-8"), dtype=np.uint8)
    name = f"checkpoint_{index:08d}.npz"
    write_atomic(folder / name, lambda f: np.savez_compressed(f, **arrays))
    return {"name": name, "index": index, "bytes": (folder / name).stat().st_size}


def _swap_in(new: Path, folder: Path) -> None:
    """Put the folder ``new`` in the place of ``folder`` (two renames; between them there is
    no cache, never a mixed one), then delete the old one."""
    old = None
    if folder.exists():
        old = folder.parent / f".{folder.name}.old-{os.getpid()}-{secrets.token_hex(4)}"
        os.rename(folder, old)
    try:
        os.rename(new, folder)
    except OSError:
        if old is not None:
            with contextlib.suppress(OSError):
                os.rename(old, folder)
        raise
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)


def _remove_leftovers(folder: Path) -> None:
    """Folders of saves that were interrupted (``.NAME.new-*``, ``.NAME.old-*``), once they
    are old enough that no save can still be writing them."""
    now = time.time()
    for p in folder.parent.glob(f".{folder.name}.*-*"):
        with contextlib.suppress(OSError):
            if p.is_dir() and now - p.stat().st_mtime > LEFTOVER_AGE_S:
                shutil.rmtree(p, ignore_errors=True)


# ------------------------------------------------------------------------------ loading
def cache_key_of(folder) -> str | None:
    """The key the manifest in ``folder`` names (None: no readable manifest of this format).
    Only a hint: ``load_checkpoints`` checks every file against the key."""
    try:
        return _manifest(Path(folder))["key"]
    except CacheError:
        return None


def load_checkpoints(timeline: Timeline, folder, key: str) -> int:
    """Give a fresh timeline the snapshots saved in ``folder`` for ``key``; returns how many.
    Everything is read and checked first: CacheError (and the timeline unchanged) when the
    cache is missing, stale, incomplete or damaged."""
    folder = Path(folder)
    m = _manifest(folder)
    if m["key"] != key:
        raise CacheError("it was made for another recording or other settings")
    loaded = []
    for entry in m["files"]:
        try:
            loaded.append(_read_snapshot(timeline, folder, entry, key))
        except (CacheError, MemoryError):
            raise
        except Exception as exc:  # a damaged zip, array or JSON: any doubt means not using it
            name = entry.get("name") if isinstance(entry, dict) else entry
            raise CacheError(f"{name} is damaged ({type(exc).__name__}: {exc})") from None
    for snap, contents in loaded:
        if snap.index in timeline.snaps:
            continue
        for tile, content in contents:
            timeline._remember(tile, snap.index, content)
        timeline.snaps[snap.index] = snap
        timeline.nbytes += snap.nbytes
    return len(loaded)


def _manifest(folder: Path) -> dict:
    path = folder / MANIFEST
    try:
        m = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise CacheError(f"there is no {MANIFEST}") from None
    except (OSError, ValueError) as exc:
        raise CacheError(f"its {MANIFEST} is unreadable ({exc})") from None
    if not isinstance(m, dict) or m.get("format") != CACHE_FORMAT:
        raise CacheError(f"its {MANIFEST} is not a checkpoint manifest")
    if m.get("version") != CACHE_VERSION:
        raise CacheError(f"it is of version {m.get('version')!r}, not {CACHE_VERSION}")
    if not isinstance(m.get("key"), str) or not isinstance(m.get("files"), list):
        raise CacheError(f"its {MANIFEST} lacks the key or the files")
    return m


def _read_snapshot(timeline: Timeline, folder: Path, entry, key: str):
    """(Snapshot, [(tile, (ink, wet, last)), ...]) of one file, checked against its manifest
    entry, the key and the paper's tiles."""
    if not isinstance(entry, dict) or not CHECKPOINT.fullmatch(str(entry.get("name"))):
        raise CacheError(f"its {MANIFEST} names a file it should not: {entry!r:.80}")
    path = folder / entry["name"]
    size = path.stat().st_size if path.is_file() else None
    if size != entry.get("bytes"):
        raise CacheError(f"{entry['name']} is missing or not the size the manifest says")
    with np.load(path, allow_pickle=False) as z:
        meta = json.loads(bytes(z["meta"]).decode("utf-8"))
        if meta.get("key") != key or meta.get("index") != entry.get("index"):
            raise CacheError(f"{entry['name']} belongs to another cache")
        brush = dict(meta["brush"])
        brush.update({k[6:]: z[k] for k in z.files if k.startswith("brush_")})
        hist = [row for row in z["predictor_history"]]
        index = int(meta["index"])
        snap = Snapshot(
            index,
            brush,
            meta["rng"],
            (hist, z["predictor_velocity"]),
            meta["paper_step"],
            _stroke_of(meta.get("paper_stroke"), entry["name"]),
        )
        contents = []
        for j, (ty, tx) in enumerate(z["tiles"].tolist()):
            content = (z[f"ink_{j}"], z[f"wet_{j}"], z[f"last_{j}"])
            _check_tile(timeline.sim.paper, (ty, tx), content, entry["name"])
            contents.append(((ty, tx), content))
            snap.tiles.add((ty, tx))
            snap.nbytes += sum(a.nbytes for a in content)
    return snap, contents


def _stroke_of(value, name: str) -> WetStroke | None:
    """The paper's stroke (``Paper.stroke``) as a checkpoint's JSON holds it (a list)."""
    if value is None:
        return None
    try:
        head, colour, land, trail = value[:5], value[5], value[6], value[7]
        return WetStroke(
            *(int(v) for v in head),
            tuple(float(c) for c in colour),
            tuple(float(v) for v in land),
            tuple(tuple(float(v) for v in at) for at in trail),
        )
    except (TypeError, ValueError, IndexError) as err:
        raise CacheError(f"{name} holds a paper stroke that is not one") from err


def _check_tile(paper, tile, content, name: str) -> None:
    """A tile lies on this paper and its arrays have the paper's shapes and types."""
    ny, nx = paper.tile_ver.shape
    ty, tx = tile
    if not (0 <= ty < ny and 0 <= tx < nx):
        raise CacheError(f"{name} holds a tile outside this paper")
    ys, xs = paper.tile_box(ty, tx)
    want = (paper.ink[ys, xs], paper.wet[ys, xs], paper.last[ys, xs])
    if any(a.shape != w.shape or a.dtype != w.dtype for a, w in zip(content, want, strict=True)):
        raise CacheError(f"{name} holds a tile of another paper")
