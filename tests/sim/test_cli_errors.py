# SPDX-License-Identifier: GPL-3.0-or-later
"""Issue 13's reproducers on the command line: every malformed input ends in one clear message
naming the field or file and exit code 2 - never a traceback, a hang or a memory blow-up."""

import copy
import json
import resource
import struct
import subprocess
import sys
import time
import zlib

import pytest

from sim.cli.main import main
from sim.core.recording import MAX_DIPS, RecordingError, from_dict, loads
from sim.image.png import PNGError, read_png
from tests.paths import ROOT

REC = {
    "format": "hairy-brush-recording",
    "version": 1,
    "paper": {"width_mm": 60, "height_mm": 40, "px_per_mm": 4, "preset": "raw_xuan"},
    "sample_rate_hz": 120,
    "seed": 3,
    "samples": [[10, 20, 34, 0, 0, 0], [12, 20, 24, 0, 0, 0], [20, 20, 24, 0, 0, 0]],
}
CHAR = json.loads((ROOT / "data" / "hanzi" / "一.json").read_text(encoding="utf-8"))
DEEP = "[" * 100_000 + "]" * 100_000


def cli(capsys, *argv):
    """(exit code, stderr) of ``python -m sim argv`` run in this process."""
    try:
        code = main([str(a) for a in argv])
    except SystemExit as exc:
        code = exc.code
    err = capsys.readouterr().err
    assert "Traceback" not in err
    return code, err


def refused(capsys, *argv, says=()):
    """The command ends with exit code 2 and one message that says every one of ``says``."""
    code, err = cli(capsys, *argv)
    assert code == 2, err
    assert "error:" in err
    for text in says:
        assert text in err, err
    return err


def write_json(path, obj):
    path.write_text(json.dumps(obj, ensure_ascii=False), encoding="utf-8")
    return path


def rec_with(**changes):
    d = copy.deepcopy(REC)
    d.update(changes)
    return d


# ------------------------------------------------------------------ recordings
def test_huge_seed_is_refused_and_a_large_one_kept(tmp_path, capsys):
    p = write_json(tmp_path / "r.json", rec_with(seed=10**400))
    refused(capsys, "render", p, "-o", tmp_path / "o.png", says=["'seed'", str(p)])
    assert from_dict(rec_with(seed=3_000_000_000)).seed == 3_000_000_000
    assert from_dict(rec_with(seed=2**64 - 1)).seed == 2**64 - 1
    with pytest.raises(RecordingError, match="'seed'"):
        from_dict(rec_with(seed=2**64))


@pytest.mark.parametrize(
    "field, value",
    [
        ("width_mm", 10**400),
        ("samples", [[10**400, 20, 34, 0, 0, 0]]),
        ("sample_rate_hz", True),
        ("samples", [[10, 20, "34", 0, 0, 0]]),
    ],
)
def test_huge_or_wrong_numbers_name_their_field(field, value):
    doc = rec_with(**{field: value}) if field != "width_mm" else copy.deepcopy(REC)
    if field == "width_mm":
        doc["paper"]["width_mm"] = value
    with pytest.raises(RecordingError, match=field):
        from_dict(doc)


def test_deeply_nested_json_is_refused_everywhere(tmp_path, capsys):
    p = tmp_path / "deep.json"
    p.write_text(DEEP)
    refused(capsys, "render", p, "-o", tmp_path / "o.png", says=["nested too deeply", str(p)])
    refused(capsys, "write", p, "-o", tmp_path / "o.png", says=["nested too deeply", str(p)])
    refused(capsys, "write", "一", "-o", tmp_path / "o.png", "--quality", p, says=["quality file"])
    with pytest.raises(RecordingError, match="nested too deeply"):
        loads(DEEP)


@pytest.mark.parametrize(
    "encode, says",
    [
        (lambda t: t.encode("utf-16"), "UTF-16"),
        (lambda t: t.encode("utf-16-le"), "not UTF-8"),
        (lambda t: b"\xff" + t.encode(), "not UTF-8"),
        (lambda t: "\ufeff".encode() + t.encode(), None),  # UTF-8 with a BOM reads
    ],
)
def test_text_that_is_not_utf8_is_refused(tmp_path, capsys, encode, says):
    rec, char = tmp_path / "r.json", tmp_path / "c.json"
    rec.write_bytes(encode(json.dumps(REC)))
    char.write_bytes(encode(json.dumps(CHAR)))
    if says is None:
        code, err = cli(capsys, "render", rec, "-o", tmp_path / "o.png", "-q")
        assert code == 0, err
        return
    refused(capsys, "render", rec, "-o", tmp_path / "o.png", says=[says, str(rec)])
    refused(capsys, "write", char, "-o", tmp_path / "o.png", says=[says, str(char)])


def test_dips_are_bounded():
    dips = [{"before_sample": 0}] * (MAX_DIPS + 1)
    t0 = time.perf_counter()
    with pytest.raises(RecordingError, match="'dips' has"):
        from_dict(rec_with(dips=dips))
    assert time.perf_counter() - t0 < 1.0
    assert len(from_dict(rec_with(dips=dips[:MAX_DIPS])).dips) == MAX_DIPS


def test_geometry_override_is_checked():
    for geometry, says in (
        ("thick", "'brush.geometry' must be an object"),
        ({"girth": 3}, "girth"),
        ({"hair_length_mm": True}, "hair_length_mm"),
        ({"hair_length_mm": 10**400}, "hair_length_mm"),
    ):
        with pytest.raises(RecordingError, match=says):
            from_dict(rec_with(brush={"preset": "mixed", "geometry": geometry}))
    rec = from_dict(rec_with(brush={"preset": "mixed", "geometry": {"hair_length_mm": 20}}))
    assert rec.resolve()[1].hair_length_mm == 20


# ------------------------------------------------------------------ character files
@pytest.mark.parametrize(
    "doc, says",
    [
        ({"strokes": [1], "medians": [[[0, 0], [1, 1]]]}, "'strokes[0]' must be an SVG path"),
        ({"strokes": [], "medians": []}, "'strokes' must be a non-empty list"),
        ({"strokes": CHAR["strokes"] * 2, "medians": CHAR["medians"]}, "one per stroke"),
        ({"strokes": ["M 0 0 Z"], "medians": CHAR["medians"]}, "no closed outline"),
        ({"strokes": ["Q 1 2 3 4 Z"], "medians": CHAR["medians"]}, "curve before any point"),
        ({"strokes": ["X 1 2"], "medians": CHAR["medians"]}, "unsupported SVG path command"),
        ({"strokes": CHAR["strokes"], "medians": [[]]}, "'medians[0]' must be a list of 1 to"),
        ({"strokes": CHAR["strokes"], "medians": [[[5, 4], [5, 4, 1]]]}, "'medians[0][1]'"),
        ({"strokes": CHAR["strokes"], "medians": [[[5, 4], [True, 1]]]}, "'medians[0][1]'"),
        ([CHAR], "not hanzi-writer data"),
    ],
)
def test_bad_character_data_names_the_field(tmp_path, capsys, doc, says):
    p = write_json(tmp_path / "c.json", doc)
    refused(capsys, "write", p, "-o", tmp_path / "o.png", says=[says, str(p)])


def test_infinite_median_is_refused(tmp_path, capsys):
    p = tmp_path / "c.json"
    p.write_text(json.dumps({"strokes": CHAR["strokes"], "medians": [[[1, 1], [float("inf"), 5]]]}))
    assert "Infinity" in p.read_text()
    refused(capsys, "write", p, "-o", tmp_path / "o.png", says=["'medians[0][1]'", "finite"])


def run_bounded(*argv, seconds=60, memory=2 << 30):
    """``python -m sim argv`` in a child with a memory limit; a hang fails the test."""

    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (memory, memory))

    t0 = time.perf_counter()
    r = subprocess.run(
        [sys.executable, "-m", "sim", *map(str, argv)],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=seconds,
        preexec_fn=limit,
    )
    assert "Traceback" not in r.stderr, r.stderr
    return r.returncode, r.stderr, time.perf_counter() - t0


def test_far_away_median_no_longer_hangs(tmp_path):
    p = tmp_path / "far.json"
    p.write_text(
        '{"strokes":["M 0 0 L 9 9 L 0 9 Z"],"medians":[[[100000,100000],[-100000,-100000]]]}'
    )
    code, err, dt = run_bounded("write", p, "-o", tmp_path / "o.png")
    assert code == 2 and "far outside the 1024-unit em box" in err and dt < 20


def test_outline_of_200k_segments_is_refused_cheaply(tmp_path):
    long_path = "M 0 0 " + "L 1 1 L 2 0 " * 100_000 + "Z"  # 1.2 MB, 200k segments
    compact = "M0 0" + "L1 1L2 0" * 2_400 + "Z"  # under the length cap, over the point cap
    for path, says in ((long_path, "characters long"), (compact, "outline points")):
        p = write_json(tmp_path / "c.json", {"strokes": [path], "medians": CHAR["medians"]})
        code, err, dt = run_bounded("write", p, "-o", tmp_path / "o.png", memory=1 << 30)
        assert code == 2 and says in err and dt < 20, err


# ------------------------------------------------------------------ quality files and presets
@pytest.mark.parametrize(
    "doc, says",
    [
        ({"e": "0.5"}, "'e' must be a number"),
        ({"quality": {"e": True}}, "'e' must be a number"),
        ({"quality": {"e": 10**400}}, "'e' must lie in [0, 1]"),
        ({"quality": {"zz": 0.5}}, "unknown quality parameter"),
        ([0.5], "needs a 'quality' object"),
    ],
)
def test_bad_quality_files_are_refused(tmp_path, capsys, doc, says):
    p = write_json(tmp_path / "q.json", doc)
    refused(capsys, "write", "一", "-o", tmp_path / "o.png", "--quality", p, says=[says, str(p)])


def test_unknown_presets_are_refused_before_work(capsys, tmp_path):
    for opt in ("--brush", "--paper", "--ink"):
        refused(capsys, "write", "一", "-o", tmp_path / "o.png", opt, "nope", says=["'nope'"])
    refused(capsys, "write", "一", "-o", tmp_path / "o.png", "--ink", "a\x00b", says=["ink"])


# ------------------------------------------------------------------ options
@pytest.mark.parametrize(
    "argv, says",
    [
        (["write", "一", "--passes", "0"], "--passes"),
        (["write", "一", "--size", "0"], "--size"),
        (["write", "一", "--size-mm", "-5"], "--size-mm"),
        (["write", "一", "--size-mm", "0"], "--size-mm"),
        (["write", "一", "--size-mm", "1e308"], "--size-mm"),
        (["write", "一", "--size-mm", "nan"], "--size-mm"),
        (["write", "一", "--seed", str(10**400)], "--seed"),
        (["write", "一", "--seed", "-1"], "--seed"),
        (["write", "一", "--size", "8192", "--size-mm", "5"], "px/mm"),
        (["write", "ab"], "neither a character data file nor a single character"),
        (["write", "一", "--data", "/nonexistent"], "does not exist"),
        (["iou", "一", "--size", "0"], "--size"),
        (["fit", "--chars", "一", "--stages", "foo"], "--stages"),
        (["fit", "--chars", "一", "--rounds", "0"], "--rounds"),
        (["fit", "--chars", "一", "--divisions", "0"], "--divisions"),
        (["fit", "--chars", "一", "--max-grid", "0"], "--max-grid"),
        (["fit", "--chars", "一", "--workers", "-1"], "--workers"),
        (["fit"], "give training characters"),
        (["fit", "--image", "a.png"], "every --image needs its --image-recording"),
        (["fit", "--chars", "一", "--seed-preset", "nope"], "'nope'"),
        (["render", "examples/strokes.json", "--px-per-mm", "0"], "--px-per-mm"),
        (["render", "examples/strokes.json", "--px-per-mm", "inf"], "--px-per-mm"),
        (["render", "examples/strokes.json", "--seed", str(10**400)], "--seed"),
        (["render", "/nonexistent.json"], "no recording file"),
    ],
)
def test_nonsense_options_are_refused(tmp_path, capsys, monkeypatch, argv, says):
    monkeypatch.chdir(ROOT)
    refused(capsys, *argv, "-o", tmp_path / "o.json", says=[says])


def test_output_folder_is_checked_before_work(capsys):
    t0 = time.perf_counter()
    refused(capsys, "write", "一", "-o", "/nonexistent/dir/o.png", says=["/nonexistent/dir"])
    assert time.perf_counter() - t0 < 2.0  # before the brush is calibrated


# ------------------------------------------------------------------ PNG files
def chunk(tag: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data))


def png(w=4, h=3, ctype=2, idat=None, depth=8, extra=b""):
    c = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}.get(ctype, 3)
    body = zlib.compress(bytes((1 + w * c) * h)) if idat is None else idat
    ihdr = chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, depth, ctype, 0, 0, 0))
    return b"\x89PNG\r\n\x1a\n" + ihdr + extra + chunk(b"IDAT", body) + chunk(b"IEND", b"")


@pytest.mark.parametrize(
    "data, says",
    [
        (png()[:8], "IHDR"),
        (png()[:40], "truncated"),
        (png()[:-1], "truncated"),
        (b"\x89PNG\r\n\x1a\n" + chunk(b"IDAT", b"x"), "IHDR"),
        (png(idat=b"not zlib at all"), "damaged"),
        (png(idat=zlib.compress(b"\x00" * 5)), "truncated"),
        (png(ctype=5), "colour type 5"),
        (png(ctype=3), "palette"),
        (
            png(
                ctype=3,
                extra=chunk(b"PLTE", bytes(3)),
                idat=zlib.compress(b"\x00\x05\x00\x00\x00" * 3),
            ),
            "index",
        ),
        (png(depth=16), "8-bit"),
        (png(idat=zlib.compress(bytes([9] + [0] * 12) * 3)), "row filter"),
        (png()[:-5] + b"\x00" * 5, "CRC"),
        (b"GIF89a", "not a PNG"),
    ],
)
def test_bad_png_files_raise_png_error(tmp_path, data, says):
    p = tmp_path / "i.png"
    p.write_bytes(data)
    with pytest.raises(PNGError, match=says):
        read_png(p)


def test_png_zlib_bomb_and_huge_image_are_refused_quickly(tmp_path):
    bomb = png(w=240, h=160, idat=zlib.compress(b"\x00" * 50_000_000, 9))
    big = png(w=3000, h=3000, idat=zlib.compress(b"\x04" + bytes(9000)))  # 1 Paeth row
    huge = png(w=30_000, h=30_000, idat=zlib.compress(bytes(100)))
    for data, says in ((bomb, "more image data"), (big, "truncated"), (huge, "too large")):
        p = tmp_path / "i.png"
        p.write_bytes(data)
        t0 = time.perf_counter()
        with pytest.raises(PNGError, match=says):
            read_png(p)
        assert time.perf_counter() - t0 < 2.0


def test_fit_checks_the_image_size_before_decoding(tmp_path, capsys):
    rec = write_json(tmp_path / "r.json", REC)  # a 240 x 160 px paper
    img = tmp_path / "i.png"
    img.write_bytes(png(w=3000, h=3000, idat=zlib.compress(bytes(3000 * 9001), 9)))
    t0 = time.perf_counter()
    argv = ["fit", "--image", img, "--image-recording", rec, "-o", tmp_path / "f.json", "-q"]
    refused(capsys, *argv, says=["3000 x 3000 px", "240 x 160 px"])
    assert time.perf_counter() - t0 < 2.0
    img.write_bytes(b"\x89PNG\r\n\x1a\n")
    refused(capsys, *argv, says=["IHDR", str(img)])


# ------------------------------------------------------------------ the library's own checks
def test_graphics_txt_lines_are_read_bounded(tmp_path):
    from sim.writing.hanzi import MAX_CHAR_BYTES, CharacterError, find_char

    good = json.dumps({"character": "一", **CHAR}, ensure_ascii=False)
    g = tmp_path / "graphics.txt"
    g.write_bytes(b"\xff\xfe junk line\n" + good.encode() + b"\n")
    assert find_char("一", g)["medians"] == CHAR["medians"]
    g.write_bytes(b'{"character":"\xe4\xb8\x80", \xff}\n')
    with pytest.raises(CharacterError, match="line 1 is not UTF-8"):
        find_char("一", g)
    g.write_bytes(b"x" * (MAX_CHAR_BYTES + 10) + b"\n" + good.encode())
    with pytest.raises(CharacterError, match="line 1 is longer than"):
        find_char("一", g)
    g.write_text(json.dumps({"character": "一", "strokes": [1], "medians": []}, ensure_ascii=False))
    with pytest.raises(CharacterError, match="line 1"):
        find_char("一", g)


def test_writer_checks_its_arguments_before_calibrating():
    from sim.core.params import ParameterError
    from sim.core.recording import Recording
    from sim.writing.writer import write_character

    template = Recording(REC["samples"])
    for kw, says in (
        ({"passes": 0}, "practice passes"),
        ({"passes": True}, "practice passes"),
        ({"n_px": 0}, "image size"),
        ({"size_mm": 0.0}, "character size"),
        ({"size_mm": float("nan")}, "character size"),
        ({"n_px": 0, "px_per_mm": 5000.0, "size_mm": 100.0}, "px_per_mm"),
        ({"n_px": 0, "px_per_mm": "5", "size_mm": 100.0}, "px_per_mm"),
        ({"n_px": 8192, "size_mm": 5.0}, "px/mm"),
        ({"n_px": 0, "px_per_mm": 100.0, "size_mm": 1000.0}, "at most 8192 px"),
    ):
        args = {"n_px": 64, "passes": 1, **kw}
        t0 = time.perf_counter()
        with pytest.raises(ParameterError, match=says):
            write_character(CHAR, args.pop("n_px"), template, **args)
        assert time.perf_counter() - t0 < 0.5  # no calibration was run


def test_bad_presets_name_the_field(tmp_path):
    from sim.core.params import ParameterError, ink_from_preset, load_preset, paper_from_preset

    (tmp_path / "inks").mkdir()
    (tmp_path / "papers").mkdir()
    for doc, kind, says in (
        ({"kind": "ink", "color": [0, 0]}, "ink", "'color'"),
        ({"kind": "ink", "wetness": "0.9"}, "ink", "'wetness'"),
        ({"kind": "ink", "radiation": 3}, "ink", "'radiation'"),
        ({"kind": "paper", "capacity": -1}, "paper", "'capacity'"),
        ({"kind": "paper", "color": [1, 1, True]}, "paper", "'color'"),
        ([1], "paper", "JSON object"),
    ):
        folder = tmp_path / ("inks" if kind == "ink" else "papers")
        (folder / "x.json").write_text(json.dumps(doc))
        build = ink_from_preset if kind == "ink" else paper_from_preset
        with pytest.raises(ParameterError, match=says):
            build(load_preset(kind, "x", tmp_path))


@pytest.mark.parametrize("channels", [1, 2, 4])
def test_fit_takes_grey_and_alpha_images(tmp_path, channels):
    import numpy as np

    from sim.fitting.samples import image_sample
    from sim.image.png import write_png

    rec = from_dict(REC)  # a 240 x 160 px paper
    img = np.random.default_rng(0).integers(0, 256, (160, 240, channels), dtype=np.uint8)
    write_png(tmp_path / "i.png", img)
    target = image_sample(rec, tmp_path / "i.png").target
    assert target.shape == (160, 240, 3)
    want = img[..., 0] if channels <= 2 else img[..., 2]
    assert np.allclose(target[..., 2], want / 255.0)


def test_samples_and_file_sizes_are_bounded(tmp_path, monkeypatch):
    import sim.core.recording
    from sim.core.jsonio import read_json

    monkeypatch.setattr(sim.core.recording, "MAX_SAMPLES", 2)
    with pytest.raises(RecordingError, match="'samples' has 3 entries; at most 2"):
        from_dict(REC)
    p = write_json(tmp_path / "r.json", REC)
    with pytest.raises(RecordingError, match="too large"):
        read_json(p, "recording", RecordingError, max_bytes=100)
