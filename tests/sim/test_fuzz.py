# SPDX-License-Identifier: GPL-3.0-or-later
"""Fuzzing the engine's inputs (issue 13): recordings, character files, quality files, presets,
PNG files and command-line options, mutated by hypothesis. Whatever comes in, loading either
succeeds - and then what was loaded works downstream - or raises the reader's own clear error
(RecordingError, CharacterError, ParameterError, PNGError; exit code 2 for options); never
anything else. Bounded: about half a minute in all."""

import contextlib
import copy
import io
import json
import os
import struct
import tempfile
import zlib
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from sim.cli.main import _parser
from sim.core.params import (
    ParameterError,
    geometry_from_preset,
    ink_from_preset,
    load_preset,
    paper_from_preset,
)
from sim.core.recording import MAX_SEED, RecordingError, from_dict, loads, quantise
from sim.fitting.search import SETTING_RANGES, load_quality
from sim.image.png import PNGError, read_png
from sim.writing.hanzi import CharacterError, check_char
from sim.writing.outline import baseline_masks, rasterise
from sim.writing.planner import plan
from sim.writing.response import Response
from sim.writing.writer import auto_size_mm
from tests.paths import ROOT

# FUZZ_EXAMPLES=5000 runs a longer campaign with the same tests
EXAMPLES = int(os.environ.get("FUZZ_EXAMPLES", "150"))
FUZZ = settings(max_examples=EXAMPLES, deadline=None, suppress_health_check=[HealthCheck.too_slow])

REC = {
    "format": "hairy-brush-recording",
    "version": 1,
    "paper": {"width_mm": 60, "height_mm": 40, "px_per_mm": 4, "preset": "raw_xuan"},
    "brush": {"preset": "mixed", "geometry": {"hair_length_mm": 25}},
    "ink": {"preset": "sumi_black"},
    "quality": {"e": 0.6},
    "sample_rate_hz": 120,
    "seed": 3,
    "samples": [[10, 20, 34, 0, 0, 0], [12, 20, 24, 0, 0, 0]],
    "dips": [{"before_sample": 0, "depth": 0.6, "color": [0, 0, 0], "wetness": 0.9}],
}
CHAR = json.loads((ROOT / "data" / "hanzi" / "人.json").read_text(encoding="utf-8"))
CHAR = {"strokes": CHAR["strokes"], "medians": CHAR["medians"]}

# anything JSON can hold, and the awkward cases of the issue among them
SCALARS = (
    st.none()
    | st.booleans()
    | st.integers(-(10**6), 10**6)
    | st.sampled_from([10**400, -(10**400), 2**64, 3_000_000_000, 0, 1, -1])
    | st.floats(allow_nan=True, allow_infinity=True)
    | st.text(max_size=6)
    | st.sampled_from(["0.5", "mixed", "M 0 0 L 9 9 L 0 9 Z", ""])
)
JSON = st.recursive(
    SCALARS,
    lambda kids: (
        st.lists(kids, max_size=4) | st.dictionaries(st.text(max_size=6), kids, max_size=3)
    ),
    max_leaves=8,
)


def _paths(node, prefix=()):
    """Every place in a JSON document (lists: their first few items)."""
    yield prefix
    if isinstance(node, dict):
        items = list(node.items())
    elif isinstance(node, list):
        items = list(enumerate(node[:4]))
    else:
        items = []
    for k, v in items:
        yield from _paths(v, prefix + (k,))


@st.composite
def mutated(draw, doc, values=JSON):
    """``doc`` with one to three places replaced by other values, or deleted."""
    d = copy.deepcopy(doc)
    for _ in range(draw(st.integers(1, 3))):
        places = list(_paths(d))
        path = draw(st.sampled_from(places[1:] or places))
        if not path:
            return draw(values)
        node = d
        for k in path[:-1]:
            node = node[k]
        if draw(st.integers(0, 5)) == 0:
            del node[path[-1]]
        else:
            node[path[-1]] = draw(values)
    return d


def flipped(data: bytes):
    """A strategy for ``data`` with a few bytes changed, or cut short."""
    n = len(data)
    edits = st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, 255)), min_size=1, max_size=4)

    def apply(args):
        changes, cut = args
        b = bytearray(data)
        for i, v in changes:
            b[i] = v
        return bytes(b[:cut])

    return st.tuples(edits, st.integers(0, n)).map(apply)


# ------------------------------------------------------------------ recordings
NUMBERS = st.floats(-300, 300) | st.integers(-10, 300) | st.sampled_from([0.0, 1.0, 0.5, 2**63])


@FUZZ
@given(doc=mutated(REC) | mutated(REC, NUMBERS))
def test_recordings_load_or_raise_recording_error(doc):
    try:
        rec = from_dict(doc)
    except RecordingError as exc:
        assert str(exc)
        return
    assert 0 <= rec.seed <= MAX_SEED and np.isfinite(rec.samples).all()
    rec.resolve()
    again = loads(json.dumps(rec.to_dict()))  # what loads saves and loads again
    assert again.seed == rec.seed and np.array_equal(again.samples, quantise(rec.samples))


@FUZZ
@given(text=flipped(json.dumps(REC).encode()))
def test_recording_text_loads_or_raises_recording_error(text):
    try:
        loads(text)
    except RecordingError:
        pass


# ------------------------------------------------------------------ character files
COORD = st.floats(-700, 1600) | st.integers(-700, 1600)
SVG = st.text(alphabet="MLQCZ0123456789.-e ,", max_size=40)
RESPONSE = Response(np.array([1.0, 5.0, 10.0]), np.array([1.0, 4.0, 8.0]), np.zeros(3), 60.0)


POINTS = st.lists(st.lists(COORD, min_size=2, max_size=2), min_size=2, max_size=5)


def _svg(points) -> str:
    """A closed outline through the points, every other piece a quadratic curve."""
    parts = [f"M {points[0][0]} {points[0][1]}"]
    for k, (x, y) in enumerate(points[1:]):
        parts.append(f"Q {x} {y} {x} {y}" if k % 2 else f"L {x} {y}")
    return " ".join(parts) + " Z"


@st.composite
def drawn_char(draw):
    """A character of one to three strokes of random shape near the em box."""
    n = draw(st.integers(1, 3))
    outlines = [_svg(draw(POINTS.filter(lambda p: len(p) >= 3))) for _ in range(n)]
    return {"strokes": outlines, "medians": [draw(POINTS) for _ in range(n)]}


@pytest.mark.slow
@FUZZ
@given(
    doc=mutated(CHAR, JSON | COORD | SVG | st.lists(st.lists(COORD, max_size=3), max_size=4))
    | mutated(CHAR, COORD)
    | drawn_char()
)
def test_characters_load_or_raise_character_error(doc):
    try:
        check_char(doc, "c.json")
    except CharacterError as exc:
        assert "c.json" in str(exc)
        return
    # accepted data goes through everything the writer does before simulating
    size = auto_size_mm(doc, RESPONSE)
    assert 20.0 <= size <= 2000.0
    pl = plan(doc, size, 0.5)
    assert np.isfinite(pl.target).all() and len(pl.strokes) == len(doc["medians"])
    assert rasterise(doc, 24).shape == (24, 24)
    assert set(baseline_masks(doc, 24)) == {"round_pen", "true_discs"}


@FUZZ
@given(text=flipped(json.dumps(CHAR).encode()))
def test_character_files_load_or_raise_character_error(text):
    from sim.writing.hanzi import load_char

    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "c.json"
        p.write_bytes(text)
        try:
            load_char(p)
        except CharacterError as exc:
            assert str(p) in str(exc)


# ------------------------------------------------------------------ quality files and presets
@FUZZ
@given(doc=mutated({"quality": {"e": 0.5, "ab": 0.2}}))
def test_quality_files_load_or_raise_parameter_error(doc):
    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "q.json"
        p.write_text(json.dumps(doc))
        try:
            q = load_quality(p)
        except ParameterError:
            return
    assert all(0.0 <= v <= 1.0 and type(v) is float for v in q.values())


PRESETS = {
    kind: json.loads((ROOT / "presets" / folder / f"{name}.json").read_text(encoding="utf-8"))
    for kind, folder, name in (
        ("brush", "brushes", "wolf_stiff"),
        ("paper", "papers", "smooth"),
        ("ink", "inks", "sumi_black"),
    )
}
FROM_PRESET = {"brush": geometry_from_preset, "paper": paper_from_preset, "ink": ink_from_preset}


@pytest.mark.slow
@FUZZ
@given(kind=st.sampled_from(sorted(PRESETS)), data=st.data())
def test_presets_load_or_raise_parameter_error(kind, data):
    doc = data.draw(mutated(PRESETS[kind]))
    folder = {"brush": "brushes", "paper": "papers", "ink": "inks"}[kind]
    with tempfile.TemporaryDirectory() as d:
        (Path(d) / folder).mkdir()
        (Path(d) / folder / "x.json").write_text(json.dumps(doc))
        try:
            FROM_PRESET[kind](load_preset(kind, "x", Path(d)))
        except ParameterError as exc:
            assert str(exc)


# ------------------------------------------------------------------ PNG files
def _chunk(tag: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data))


def _filtered(img: np.ndarray, filters) -> bytes:
    """Rows of ``img`` (H, W, C) under the given PNG filter types, as an encoder writes them."""
    h, w, c = img.shape
    a = img.astype(np.int32).reshape(h, w * c)
    out = []
    for y in range(h):
        cur, up = a[y], (a[y - 1] if y else np.zeros_like(a[y]))
        left = np.concatenate([np.zeros(c, np.int32), cur[:-c]])
        ul = np.concatenate([np.zeros(c, np.int32), up[:-c]])
        p = left + up - ul
        pa, pb, pc = abs(p - left), abs(p - up), abs(p - ul)
        paeth = np.where((pa <= pb) & (pa <= pc), left, np.where(pb <= pc, up, ul))
        pred = [0, left, up, (left + up) >> 1, paeth][filters[y % len(filters)]]
        out.append(
            bytes([filters[y % len(filters)]]) + ((cur - pred) & 255).astype(np.uint8).tobytes()
        )
    return b"".join(out)


def _png(ihdr: bytes, idat: bytes, extra: bytes = b"") -> bytes:
    return (
        b"\x89PNG\r\n\x1a\n"
        + _chunk(b"IHDR", ihdr)
        + extra
        + _chunk(b"IDAT", idat)
        + _chunk(b"IEND", b"")
    )


def _read(data: bytes):
    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "i.png"
        p.write_bytes(data)
        return read_png(p)


@settings(max_examples=max(EXAMPLES // 2, 1), deadline=None)
@given(
    w=st.integers(1, 9),
    h=st.integers(1, 9),
    c=st.sampled_from([1, 2, 3, 4]),
    filters=st.lists(st.integers(0, 4), min_size=1, max_size=9),
    seed=st.integers(0, 2**32 - 1),
)
def test_png_rows_under_every_filter_decode_exactly(w, h, c, filters, seed):
    img = np.random.default_rng(seed).integers(0, 256, (h, w, c), dtype=np.uint8)
    ctype = {1: 0, 2: 4, 3: 2, 4: 6}[c]
    data = _png(
        struct.pack(">IIBBBBB", w, h, 8, ctype, 0, 0, 0), zlib.compress(_filtered(img, filters))
    )
    assert np.array_equal(_read(data), img)


@FUZZ
@given(
    w=st.integers(0, 2**32 - 1) | st.integers(1, 8),
    h=st.integers(0, 2**32 - 1) | st.integers(1, 8),
    depth=st.sampled_from([1, 2, 4, 8, 16, 0, 255]),
    ctype=st.integers(0, 7),
    flags=st.tuples(st.integers(0, 1), st.integers(0, 1), st.integers(0, 1)),
    body=st.binary(max_size=200),
    compress=st.booleans(),
    palette=st.binary(max_size=12),
)
def test_png_headers_read_or_raise_png_error(w, h, depth, ctype, flags, body, compress, palette):
    ihdr = struct.pack(">IIBBBBB", w, h, depth, ctype, *flags)
    extra = _chunk(b"PLTE", palette) if palette else b""
    data = _png(ihdr, zlib.compress(body) if compress else body, extra)
    try:
        img = _read(data)
    except PNGError as exc:
        assert "i.png" in str(exc)
        return
    assert img.shape[:2] == (h, w) and img.dtype == np.uint8


RAW = _filtered(np.arange(60, dtype=np.uint8).reshape(4, 5, 3), [0, 1, 3, 4])
GOOD_PNG = _png(struct.pack(">IIBBBBB", 5, 4, 8, 2, 0, 0, 0), zlib.compress(RAW))


@FUZZ
@given(data=flipped(GOOD_PNG))
def test_damaged_png_files_read_or_raise_png_error(data):
    try:
        img = _read(data)
    except PNGError:
        return
    assert img.shape == (4, 5, 3)


@FUZZ
@given(raw=flipped(RAW))
def test_png_image_data_reads_or_raises_png_error(raw):
    """Damage inside the image data, the chunks sound: bad row filters, too little data."""
    data = _png(struct.pack(">IIBBBBB", 5, 4, 8, 2, 0, 0, 0), zlib.compress(raw))
    try:
        img = _read(data)
    except PNGError as exc:
        assert "filter" in str(exc) or "truncated" in str(exc)
        return
    assert img.shape == (4, 5, 3)


# ------------------------------------------------------------------ command-line options
OPTIONS = {
    "--passes": "passes",
    "--size": "size",
    "--size-mm": "size_mm",
    "--seed": "seed",
    "--rounds": "rounds",
    "--divisions": "divisions",
    "--max-grid": "max_grid",
    "--workers": "workers",
    "--iterations": "iterations",
    "--stages": "stages",
}
VALUES = (
    st.sampled_from(
        [
            "0",
            "-1",
            "1",
            "2",
            "4",
            "8",
            "64",
            "1e308",
            "nan",
            "inf",
            "-5",
            "0.5",
            str(10**400),
            "",
            "foo",
            "qp1",
            "qp2,qp1",
            "qp1,foo",
            "8192",
            "8193",
            str(2**64 - 1),
            str(2**64),
        ]
    )
    | st.integers(-(10**20), 10**20).map(str)
    | st.floats().map(str)
)


@pytest.mark.slow
@settings(max_examples=2 * EXAMPLES, deadline=None)
@given(opt=st.sampled_from(sorted(OPTIONS)), value=VALUES)
def test_options_parse_in_range_or_exit_2(opt, value):
    argv = ["fit", "--chars", "一", "-o", "f.json", opt, value]
    err = io.StringIO()
    try:
        with contextlib.redirect_stderr(err):
            args = _parser().parse_args(argv)
    except SystemExit as exc:
        assert exc.code == 2
        assert "error: argument " + opt in err.getvalue()
        return
    v = getattr(args, OPTIONS[opt])
    name = OPTIONS[opt]
    if name in SETTING_RANGES:
        lo, hi = SETTING_RANGES[name]
        assert lo <= v <= hi
    elif name == "stages":
        assert v and set(v) <= {"qp1", "qp2"}
    elif name == "seed":
        assert 0 <= v <= MAX_SEED
    else:
        assert np.isfinite(v) and v > 0


@pytest.mark.parametrize("name", ["recording", "character"])
def test_fuzz_documents_are_valid_as_given(name):
    """The fuzzers start from sound documents (so that mutations, not the seeds, are refused)."""
    if name == "recording":
        assert from_dict(REC).resolve()[1].hair_length_mm == 25
    else:
        assert check_char(CHAR, "人") is CHAR
