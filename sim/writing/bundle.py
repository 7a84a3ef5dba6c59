# SPDX-License-Identifier: GPL-3.0-or-later
"""The bundled stroke data: every character of hanzi-writer-data 2.0.1 (9,574, simplified and
traditional; Arphic Public License, ``ARPHICPL.TXT`` beside it) in one file, read lazily.

The file: ``MAGIC``, the number of characters n (u32), their code points sorted (n x u32), the
offsets of their records (n + 1 x u32, from the end of the index) and the records. A record is
one character's data, compact-coded (``encode``) and deflated on its own, so a lookup is a
binary search of the code points and the decoding of one record: milliseconds, whatever the
size of the set. Numbers are little-endian.

The compact code keeps the data exactly: an SVG outline of absolute M, L, Q, C, Z with whole
numbers separated by single spaces (as hanzi-writer-data writes them) is kept as its commands
and the points' differences; anything else (a fraction, other spacing) keeps its JSON text.
``scripts/build_hanzi_bundle.py`` writes the file and checks that every character decodes to
its source."""

from __future__ import annotations

import json
import re
import struct
import threading
import zlib
from pathlib import Path

import numpy as np

MAGIC = b"HWDB\x01\n"
_CMDS = "MLQCZ"
_ARGS = {"M": 2, "L": 2, "Q": 4, "C": 6, "Z": 0}
_TOKEN = re.compile(r"[A-Za-z]|-?\d+")
COMPACT, JSON_TEXT = 0, 1  # a record's first byte
MAX_RECORD_BYTES = 1 << 20  # a record (the largest of hanzi-writer-data is under 3 kB)


class BundleError(ValueError):
    """The bundle file is damaged or not a bundle."""


# ---------------------------------------------------------------------------------- encode
def _varint(out: bytearray, u: int) -> None:
    while u >= 0x80:
        out.append((u & 0x7F) | 0x80)
        u >>= 7
    out.append(u)


def _signed(out: bytearray, v: int) -> None:
    _varint(out, (v << 1) if v >= 0 else ((-v) << 1) - 1)  # zigzag


def _points(out: bytearray, nums) -> None:
    px = py = 0
    for k in range(0, len(nums), 2):
        x, y = nums[k], nums[k + 1]
        _signed(out, x - px)
        _signed(out, y - py)
        px, py = x, y


def _path_code(path) -> tuple[bytes, list] | None:
    """(command bytes, whole numbers) of a canonical SVG path, None for any other."""
    if not isinstance(path, str):
        return None
    toks = _TOKEN.findall(path)
    if " ".join(toks) != path:
        return None
    cmds, nums, i = bytearray(), [], 0
    while i < len(toks):
        c = toks[i]
        if c not in _ARGS or (_ARGS[c] and i + _ARGS[c] >= len(toks)):
            return None
        args = toks[i + 1 : i + 1 + _ARGS[c]]
        if any(a in _ARGS for a in args):
            return None
        cmds.append(_CMDS.index(c))
        nums += [int(a) for a in args]
        i += 1 + len(args)
    return bytes(cmds), nums


def _whole_points(med) -> bool:
    return isinstance(med, list) and all(
        isinstance(p, list) and len(p) == 2 and all(type(v) is int for v in p) for p in med
    )


def encode(char: dict) -> bytes:
    """One character's record before deflating: compact when the data allows it exactly, else
    its JSON text."""
    keys = set(char)
    strokes, medians = char.get("strokes"), char.get("medians")
    rad = char.get("radStrokes")
    codes = [_path_code(p) for p in strokes] if isinstance(strokes, list) else [None]
    ok = (
        keys in ({"strokes", "medians"}, {"strokes", "medians", "radStrokes"})
        and all(c is not None for c in codes)
        and isinstance(medians, list)
        and len(medians) == len(strokes)
        and all(_whole_points(m) for m in medians)
        and (rad is None or (isinstance(rad, list) and all(type(r) is int and r >= 0 for r in rad)))
    )
    if not ok:
        return bytes([JSON_TEXT]) + json.dumps(char, separators=(",", ":")).encode("utf-8")
    out = bytearray([COMPACT])
    _varint(out, len(strokes))
    for cmds, nums in codes:
        _varint(out, len(cmds))
        out += cmds
        _points(out, nums)
    for med in medians:
        _varint(out, len(med))
        _points(out, [v for p in med for v in p])
    if rad is None:
        out.append(0)
    else:
        out.append(1)
        _varint(out, len(rad))
        for r in rad:
            _varint(out, r)
    return bytes(out)


def write_bundle(path, chars: dict) -> int:
    """Write ``chars`` ({character: data}) as a bundle; returns its size in bytes."""
    order = sorted(chars, key=ord)
    records = []
    for c in order:
        if len(c) != 1:
            raise BundleError(f"{c!r} is not a single character")
        rec = zlib.compress(encode(chars[c]), 9)
        records.append(rec)
    offsets = np.concatenate([[0], np.cumsum([len(r) for r in records])]).astype("<u4")
    head = MAGIC + struct.pack("<I", len(order))
    body = np.array([ord(c) for c in order], dtype="<u4").tobytes() + offsets.tobytes()
    data = head + body + b"".join(records)
    Path(path).write_bytes(data)
    return len(data)


# ---------------------------------------------------------------------------------- decode
class _Reader:
    """Reads varints from a record."""

    def __init__(self, data: bytes, at: int = 1):
        self.data, self.at = data, at

    def uint(self) -> int:
        shift = value = 0
        data = self.data
        while True:
            b = data[self.at]
            self.at += 1
            value |= (b & 0x7F) << shift
            if b < 0x80:
                return value
            shift += 7

    def points(self, n: int) -> list:
        out, px, py = [], 0, 0
        for _ in range(n):
            u, v = self.uint(), self.uint()
            px += (u >> 1) ^ -(u & 1)
            py += (v >> 1) ^ -(v & 1)
            out.append([px, py])
        return out


def decode(record: bytes) -> dict:
    """The character data of a record (before deflating: ``encode``'s output)."""
    if record[0] == JSON_TEXT:
        return json.loads(record[1:].decode("utf-8"))
    if record[0] != COMPACT:
        raise BundleError(f"unknown record kind {record[0]}")
    r = _Reader(record)
    strokes = []
    for _ in range(r.uint()):
        n = r.uint()
        cmds = [_CMDS[k] for k in record[r.at : r.at + n]]
        r.at += n
        pts = iter(r.points(sum(_ARGS[c] for c in cmds) // 2))
        parts = []
        for c in cmds:
            parts.append(c)
            for _ in range(_ARGS[c] // 2):
                x, y = next(pts)
                parts += [str(x), str(y)]
        strokes.append(" ".join(parts))
    medians = [r.points(r.uint()) for _ in strokes]
    out = {"strokes": strokes, "medians": medians}
    if record[r.at]:
        r.at += 1
        out["radStrokes"] = [r.uint() for _ in range(r.uint())]
    return out


class Bundle:
    """A bundle file, opened on the first lookup: the index (code points and offsets) is read
    once, each character's record when it is asked for."""

    def __init__(self, path):
        self.path = Path(path)
        self._index = None
        self._lock = threading.Lock()

    def _load_index(self):
        with self._lock:
            if self._index is not None:
                return self._index
            try:
                with open(self.path, "rb") as fh:
                    head = fh.read(len(MAGIC) + 4)
                    if len(head) < len(MAGIC) + 4 or not head.startswith(MAGIC):
                        raise BundleError(f"{self.path} is not a stroke data bundle")
                    (n,) = struct.unpack("<I", head[len(MAGIC) :])
                    body = fh.read(4 * (2 * n + 1))
            except OSError as exc:
                raise BundleError(f"cannot read {self.path}: {exc.strerror or exc}") from None
            if len(body) != 4 * (2 * n + 1):
                raise BundleError(f"{self.path} is truncated")
            codes = np.frombuffer(body, dtype="<u4", count=n)
            offsets = np.frombuffer(body, dtype="<u4", offset=4 * n)
            self._index = (codes, offsets, len(MAGIC) + 4 + len(body))
            return self._index

    def __len__(self) -> int:
        return len(self._load_index()[0])

    def characters(self) -> str:
        return "".join(map(chr, self._load_index()[0].tolist()))

    def __contains__(self, char) -> bool:
        return self._find(char) is not None

    def _find(self, char):
        if not isinstance(char, str) or len(char) != 1:
            return None
        codes, _, _ = self._load_index()
        i = int(np.searchsorted(codes, ord(char)))
        return i if i < len(codes) and codes[i] == ord(char) else None

    def record(self, char: str) -> bytes | None:
        """The raw (inflated, still compact-coded) record of ``char``; None when absent."""
        i = self._find(char)
        if i is None:
            return None
        _, offsets, start = self._load_index()
        a, b = int(offsets[i]), int(offsets[i + 1])
        if not 0 < b - a <= MAX_RECORD_BYTES:
            raise BundleError(f"{self.path}: the record of {char!r} is damaged")
        try:
            with open(self.path, "rb") as fh:
                fh.seek(start + a)
                data = fh.read(b - a)
            return zlib.decompress(data)
        except (OSError, zlib.error) as exc:
            raise BundleError(f"{self.path}: cannot read the record of {char!r}: {exc}") from None

    def get(self, char: str) -> dict | None:
        """The character's data (not yet checked: ``hanzi.check_char``), None when absent."""
        rec = self.record(char)
        return None if rec is None else decode(rec)
