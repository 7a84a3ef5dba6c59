# SPDX-License-Identifier: GPL-3.0-or-later
"""Character stroke data (hanzi-writer-data / Make Me a Hanzi): medians as brush paths.

Coordinates in the data: a 1024-unit em box, y up, with image y = 900 - y_data. On the paper
(mm, y up) the em box maps onto a square of ``size_mm`` whose top edge is y_data = 900."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np

from ..core.jsonio import decode_text, parse_json, read_json
from ..core.params import HOVER_MM, number_within
from .outline import EM, TOP, parse_path
from .strokes import stroke, travel

MAX_CHAR_BYTES = 4 * 2**20  # a character file, or a line of graphics.txt
MAX_STROKES = 64
MAX_OUTLINE_CHARS = 20_000  # a stroke's SVG path (the bundled ones: under 500)
MAX_OUTLINE_POINTS = 2_000  # a stroke's outline with its curves flattened (bundled: under 200)
MAX_MEDIAN_POINTS = 256  # (bundled: under 20)
MAX_MEDIAN_LENGTH = 4 * EM  # data units along one median (bundled: under 1.4 EM)
MAX_TOTAL_LENGTH = 32 * EM  # along all the medians of a character
COORD_MARGIN = EM / 2  # how far outside the em box a point may lie
_X_RANGE = (-COORD_MARGIN, EM + COORD_MARGIN)
_Y_RANGE = (TOP - EM - COORD_MARGIN, TOP + COORD_MARGIN)


class CharacterError(ValueError):
    """Character data is unreadable or malformed; the message names the file and the field."""


def _check_points(pts, where: str) -> None:
    """Every point finite and near the em box (far-off points would ask for endless writing)."""
    (xlo, xhi), (ylo, yhi) = _X_RANGE, _Y_RANGE
    bad = ~((pts[:, 0] >= xlo) & (pts[:, 0] <= xhi) & (pts[:, 1] >= ylo) & (pts[:, 1] <= yhi))
    if bad.any():
        x, y = pts[int(np.argmax(bad))]
        raise CharacterError(
            f"{where}: point ({x:.6g}, {y:.6g}) lies far outside the 1024-unit em box "
            f"(x in [{xlo:g}, {xhi:g}], y in [{ylo:g}, {yhi:g}])"
        )


def _check_outline(path, where: str) -> None:
    if not isinstance(path, str):
        raise CharacterError(f"{where} must be an SVG path (a string)")
    if len(path) > MAX_OUTLINE_CHARS:
        raise CharacterError(f"{where} is {len(path)} characters long; at most {MAX_OUTLINE_CHARS}")
    try:
        polys = parse_path(path)
    except ValueError as exc:
        raise CharacterError(f"{where}: {exc}") from None
    if not polys:
        raise CharacterError(f"{where} has no closed outline of three points or more")
    pts = np.concatenate(polys)
    if len(pts) > MAX_OUTLINE_POINTS:
        raise CharacterError(f"{where} has {len(pts)} outline points; at most {MAX_OUTLINE_POINTS}")
    _check_points(pts, where)


def _check_median(med, src: str, i: int) -> float:
    """Median i: 1 or more [x, y] points near the em box (one: a dot); returns its length."""
    where = f"{src}: 'medians[{i}]'"
    if not isinstance(med, list) or not 1 <= len(med) <= MAX_MEDIAN_POINTS:
        raise CharacterError(f"{where} must be a list of 1 to {MAX_MEDIAN_POINTS} points [x, y]")
    for k, p in enumerate(med):
        if not (isinstance(p, list) and len(p) == 2 and all(number_within(v) for v in p)):
            raise CharacterError(
                f"{src}: 'medians[{i}][{k}]' must be a point [x, y] of two finite numbers"
            )
    pts = np.array(med, dtype=float)
    _check_points(pts, where)
    length = float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())
    if length > MAX_MEDIAN_LENGTH:
        raise CharacterError(
            f"{where} is {length:.0f} units long; at most {MAX_MEDIAN_LENGTH:.0f} (4 em boxes)"
        )
    return length


def check_char(d, where: str) -> dict:
    """Character data as the writer needs it, checked: 'strokes' (SVG outlines) and 'medians'
    (the brush's paths), one of each per stroke, bounded in size. Raises CharacterError."""
    if not isinstance(d, dict) or "medians" not in d or "strokes" not in d:
        raise CharacterError(f"{where}: not hanzi-writer data (needs 'strokes' and 'medians')")
    strokes, medians = d["strokes"], d["medians"]
    for key, v in (("strokes", strokes), ("medians", medians)):
        if not isinstance(v, list) or not v:
            raise CharacterError(f"{where}: '{key}' must be a non-empty list")
    if len(strokes) > MAX_STROKES:
        raise CharacterError(f"{where}: {len(strokes)} strokes; at most {MAX_STROKES}")
    if len(medians) != len(strokes):
        raise CharacterError(
            f"{where}: {len(strokes)} 'strokes' but {len(medians)} 'medians' (one per stroke)"
        )
    for i, path in enumerate(strokes):
        _check_outline(path, f"{where}: 'strokes[{i}]'")
    total = sum(_check_median(m, where, i) for i, m in enumerate(medians))
    if total > MAX_TOTAL_LENGTH:
        raise CharacterError(
            f"{where}: the medians are {total:.0f} units long together; "
            f"at most {MAX_TOTAL_LENGTH:.0f}"
        )
    return d


def load_char(path) -> dict:
    """Checked character data from a hanzi-writer JSON file."""
    p = Path(path)
    return check_char(read_json(p, "character data", CharacterError, MAX_CHAR_BYTES), str(p))


DATA_DIR = Path(__file__).resolve().parents[2] / "data" / "hanzi"
# all of hanzi-writer-data 2.0.1 (sim.writing.bundle; scripts/build_hanzi_bundle.py rebuilds it)
BUNDLE = DATA_DIR / "hanzi-writer-data.bin"


def find_char(spec: str, data=None) -> dict:
    """Character data from a path to a hanzi-writer JSON file, or from a character looked up
    (``lookup``) in the user's ``data`` - a folder of hanzi-writer-data files (``<char>.json``)
    or Make Me a Hanzi's ``graphics.txt`` (one JSON object per line with a "character" key) -
    and then in the bundled set. Raises CharacterError."""
    if not isinstance(spec, str) or not spec:
        raise CharacterError("give a character, or a character data file")
    p = Path(spec)
    if p.suffix == ".json" and p.is_file():
        return load_char(p)
    if len(spec) != 1:
        raise CharacterError(f"{spec!r} is neither a character data file nor a single character")
    char = lookup(spec, data)
    if char is None:
        where = f"{data} nor in the bundled set" if data else "the bundled set"
        raise CharacterError(f"no data for {spec!r} in {where}")
    return char


def lookup(char: str, data=None) -> dict | None:
    """The checked data of one character: the user's ``data`` (a folder of ``<char>.json`` or a
    graphics.txt) wins; then the bundled set (``BUNDLE``; the sixteen files of ``DATA_DIR``
    when it is absent). None when neither has it; a damaged file raises CharacterError."""
    if data:
        src = Path(data)
        if src.is_dir():
            f = src / f"{char}.json"
            if f.is_file():
                return load_char(f)
        elif src.is_file():
            found = _graphics_line(src, char)
            if found is not None:
                return found
        else:
            raise CharacterError(f"character data {src} does not exist")
    return _builtin(char)


_BUNDLES: dict = {}
_CHECKED: set = set()  # characters of the bundle whose data has passed check_char


def _builtin(char: str) -> dict | None:
    """A character of the bundled set, checked once per process (the bundle does not change)."""
    from .bundle import Bundle, BundleError

    if not BUNDLE.is_file():
        f = DATA_DIR / f"{char}.json"
        return load_char(f) if len(char) == 1 and f.is_file() else None
    bundle = _BUNDLES.setdefault(BUNDLE, Bundle(BUNDLE))
    try:
        d = bundle.get(char)
    except BundleError as exc:
        raise CharacterError(str(exc)) from None
    if d is not None and char not in _CHECKED:
        check_char(d, f"{BUNDLE.name}: {char!r}")
        _CHECKED.add(char)
    return d


def _graphics_line(src: Path, spec: str) -> dict | None:
    """The checked data of ``spec`` from Make Me a Hanzi's graphics.txt (a JSON object a line),
    found through an index of the file's lines made once (``_graphics_index``); None when the
    file has no line for it."""
    n, offset = _graphics_index(src).get(spec, (0, -1))
    if n == 0:
        return None
    where = f"{src} line {n}"
    try:
        with open(src, "rb") as fh:
            fh.seek(offset)
            line = fh.readline(MAX_CHAR_BYTES + 1)
    except OSError as exc:
        raise CharacterError(f"cannot read character data {src}: {exc.strerror or exc}") from None
    d = parse_json(decode_text(line, where, CharacterError), where, CharacterError)
    if not isinstance(d, dict) or d.get("character") != spec:
        raise CharacterError(f"{where}: not the data of {spec!r} (the file changed?)")
    return check_char(d, where)


_CHAR_KEY = re.compile(rb'"character"\s*:\s*("(?:[^"\\]|\\.)*")')
_INDEXES: dict = {}


def _graphics_index(src: Path) -> dict:
    """{character: (line number, byte offset)} of a graphics.txt, read a bounded line at a
    time once per version of the file (the first line of a character wins)."""
    try:
        st = src.stat()
        key = (str(src.resolve()), st.st_size, st.st_mtime_ns)
        if key in _INDEXES:
            return _INDEXES[key]
        index, offset = {}, 0
        with open(src, "rb") as fh:
            for n, line in enumerate(iter(lambda: fh.readline(MAX_CHAR_BYTES + 1), b""), 1):
                if len(line) > MAX_CHAR_BYTES:
                    raise CharacterError(f"{src} line {n} is longer than {MAX_CHAR_BYTES} bytes")
                m = _CHAR_KEY.search(line)
                if m:
                    try:
                        c = json.loads(m.group(1).decode("utf-8"))
                    except ValueError:
                        c = None
                    if isinstance(c, str):
                        index.setdefault(c, (n, offset))
                offset += len(line)
    except OSError as exc:
        raise CharacterError(f"cannot read character data {src}: {exc.strerror or exc}") from None
    _INDEXES[key] = index
    return index


def to_paper(points, size_mm: float, origin=(0.0, 0.0)) -> np.ndarray:
    """Data units -> paper mm (y up): the em box [0, 1024] x [900 - 1024, 900] fills the square."""
    pts = np.asarray(points, dtype=float)
    s = size_mm / EM
    return np.stack([origin[0] + pts[:, 0] * s, origin[1] + (pts[:, 1] - (TOP - EM)) * s], axis=1)


def simple_samples(
    char: dict,
    size_mm: float,
    hair_length_mm: float,
    press_mm: float = 9.0,
    speed_mm_s: float = 70.0,
    rate_hz: float = 120.0,
) -> np.ndarray:
    """A plain trajectory: each median written at constant press, the brush lifted between."""
    hover = hair_length_mm + HOVER_MM
    parts, prev = [], None
    for med in char["medians"]:
        pts = to_paper(med, size_mm)
        if prev is not None:
            parts.append(travel(prev, pts[0], 20, hover))
        parts.append(
            stroke(
                pts,
                rate_hz=rate_hz,
                speed_mm_s=speed_mm_s,
                press_mm=press_mm,
                hair_length_mm=hair_length_mm,
            )
        )
        prev = pts[-1]
    return np.concatenate(parts)


def character_recording(path, size_mm: float = 160.0, px_per_mm: float = 6.0):
    """The demo's recording: one character written by the soft goat-hair brush on raw xuan."""
    from ..core.recording import Dip, Recording

    samples = simple_samples(load_char(path), size_mm, hair_length_mm=34.0, press_mm=14.0)
    return Recording(
        samples,
        width_mm=size_mm,
        height_mm=size_mm,
        px_per_mm=px_per_mm,
        brush={"preset": "goat_soft"},
        paper_preset="raw_xuan",
        dips=[Dip(0, 0.9, (0.03, 0.03, 0.04), 0.95)],
    )
