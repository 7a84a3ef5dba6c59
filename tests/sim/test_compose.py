# SPDX-License-Identifier: GPL-3.0-or-later
"""``python -m sim compose`` (issue 27): a short text at a small size through the command line -
the layout JSON against the ink, bit-identical re-rendering from the saved recording, the grid,
the seal, the message for characters without stroke data, on a Dask cluster as here."""

import json
import time

import numpy as np
import pytest

from sim.cli.main import main
from sim.image.png import read_png

SMALL = ["--char-mm", "24", "--char-size", "40", "--passes", "1", "--workers", "1", "-q"]


def compose(tmp_path, name, *args):
    out = tmp_path / f"{name}.png"
    lay = tmp_path / f"{name}.json"
    rec = tmp_path / f"{name}_rec.json"
    argv = ["compose", *args, "-o", out, "--layout-out", lay, "--save-recording", rec, *SMALL]
    assert main([str(a) for a in argv]) == 0
    return read_png(out), json.loads(lay.read_text(encoding="utf-8"))["items"], rec, out


@pytest.fixture(scope="module")
def signed(tmp_path_factory):
    """山水 / 大 in columns, signed 人 and sealed 永 (白文), on a 米字格 practice sheet."""
    tmp = tmp_path_factory.mktemp("signed")
    args = ["山水\n大", "--signature", "人", "--seal", "永", "--grid", "mi", "--seed", "3"]
    return compose(tmp, "signed", *args)


def ink_mask(img) -> np.ndarray:
    """Pixels of ink: grey (not the red of a seal or a grid) and darker than the paper."""
    a = img.astype(int)
    grey = a.max(axis=2) - a.min(axis=2) < 40
    return grey & (a.mean(axis=2) < np.median(a.mean(axis=2)) - 40)


def inside(mask, box):
    x0, y0, x1, y1 = box
    m = np.zeros_like(mask)
    m[y0:y1, x0:x1] = True
    return m


@pytest.mark.slow
def test_the_layout_json_holds_every_character_and_its_ink(signed):
    img, items, _, _ = signed
    assert [(i["char"], i["role"]) for i in items] == [
        ("山", "text"),
        ("水", "text"),
        ("大", "text"),
        ("人", "signature"),
        ("永", "seal"),
    ]
    h, w = img.shape[:2]
    ink = ink_mask(img)
    covered = np.zeros_like(ink)
    for item in items[:-1]:
        x0, y0, x1, y1 = item["box"]
        assert 0 <= x0 < x1 <= w and 0 <= y0 < y1 <= h
        assert (ink & inside(ink, item["box"])).sum() > 10, item  # its ink is there
        covered |= inside(ink, item["box"])
    assert ink.sum() > 200 and not (ink & ~covered).any()  # and no ink is anywhere else
    (shan, shui, da) = (i["box"] for i in items[:3])
    assert shan[0] == shui[0] and shan[1] < shui[1]  # one column, top to bottom
    assert da[2] <= shan[0] + 2  # the next column to the left
    sig = items[3]["box"]
    assert sig[2] <= da[0] + 2 and (sig[2] - sig[0]) < (da[2] - da[0])  # smaller, left of it


@pytest.mark.slow
def test_the_saved_recording_renders_the_same_sheet_bit_for_bit(signed, tmp_path):
    img, _, rec, _ = signed
    again = tmp_path / "again.png"
    assert main(["render", str(rec), "-o", str(again), "-q"]) == 0
    assert np.array_equal(read_png(again), img)
    d = json.loads(rec.read_text(encoding="utf-8"))
    assert d["work"]["layout"]["grid"] == "mi" and d["work"]["seal_glyphs"]
    assert all("restart" in dp for dp in d["dips"])  # one brush: a restarting dip a cell


def _reddish(img):
    a = img.astype(int)
    return (a[..., 0] - a[..., 1] > 25) & (a[..., 0] - a[..., 2] > 25)


@pytest.mark.slow
def test_the_grid_is_printed_faintly_in_red_under_each_cell(signed):
    from sim.core.recording import load
    from sim.writing.work.layout import Layout

    img, items, rec_path, _ = signed
    rec = load(rec_path)
    lay = Layout.from_dict(rec.extra["work"]["layout"])
    red = _reddish(img)
    seal = inside(red, items[-1]["box"])
    H, ppm = rec.height_px, rec.px_per_mm
    boxes = lay.grid_boxes()
    assert len(boxes) == 4  # two columns of two: the grid of the text's lines
    for x0, y0, x1, y1 in boxes:
        col = int(round((x0 + x1) / 2 * ppm))
        top = int(round(H - y1 * ppm))
        left = int(round(x0 * ppm))
        row = int(round(H - (y0 + y1) / 2 * ppm))
        assert red[max(top - 1, 0) : top + 2, col - 3 : col + 4].any()  # the border
        assert red[row - 3 : row + 4, max(left - 1, 0) : left + 2].any()
    faint = img[red & ~seal].astype(int)
    assert faint.size and faint.min(axis=1).min() > 90  # faint: never as dark as ink


@pytest.mark.slow
def test_the_seal_is_red_square_and_unevenly_printed(signed):
    img, items, _, _ = signed
    x0, y0, x1, y1 = items[-1]["box"]
    patch = img[y0:y1, x0:x1].astype(int)
    red = (patch[..., 0] > 140) & (patch[..., 1] < 120) & (patch[..., 2] < 110)
    share = red.mean()
    assert 0.3 < share < 0.9, share  # 白文: red stone, the carved character and specks blank
    rows, cols = np.nonzero(red)
    side_h, side_w = np.ptp(rows), np.ptp(cols)
    assert abs(side_h - side_w) <= 0.15 * max(side_h, side_w)  # square
    assert patch[red][:, 0].std() > 4  # not a flat red: the paste lies unevenly


@pytest.mark.slow
def test_a_horizontal_work_keeps_its_marks_and_reads_in_rows(tmp_path):
    img, items, _, _ = compose(
        tmp_path, "h", "山，水", "--layout", "horizontal", "--punctuation", "keep"
    )
    assert [i["char"] for i in items] == ["山", "，", "水"]
    (shan, comma, shui) = (i["box"] for i in items)
    assert shan[1] == comma[1] == shui[1] and shan[0] < comma[0] < shui[0]
    ink = ink_mask(img)
    x0, y0, x1, y1 = comma
    mark = ink[y0:y1, x0:x1]
    rows, cols = np.nonzero(mark)
    assert rows.size and rows.mean() > (y1 - y0) / 2 and cols.mean() < (x1 - x0) / 2  # low left
    assert not _reddish(img).any()  # no grid, no seal


def test_characters_without_stroke_data_are_named_in_one_message(tmp_path, capsys, monkeypatch):
    import sim.writing.response

    def no_calibration(*a, **k):
        raise AssertionError("the brush was calibrated before the text was checked")

    monkeypatch.setattr(sim.writing.response, "calibrate", no_calibration)
    out = tmp_path / "x.png"
    rc = main(["compose", "山A水😀x，", "-o", str(out), *SMALL])
    err = capsys.readouterr().err
    assert rc == 2 and not out.exists()
    assert (
        "Traceback" not in err and err.count("error:") == 1 and len(err.strip().splitlines()) == 1
    )
    for named in ("'A'", "'😀'", "'x'", "--skip-missing"):
        assert named in err
    assert "'，'" not in err  # punctuation is left out, not missing


@pytest.mark.slow
def test_skip_missing_leaves_them_out_and_says_so(tmp_path, capsys):
    _, items, _, _ = compose(tmp_path, "s", "A一", "--skip-missing")
    assert [i["char"] for i in items] == ["一"]
    assert "'A'" in capsys.readouterr().err


@pytest.mark.parametrize(
    "args, says",
    [
        (["--dpi", "100"], "--dpi goes with --paper"),
        (["--paper", "A4", "--char-mm", "30"], "--char-mm and --paper"),
        (["--paper", "Q9"], "unknown paper"),
        (["--text-file", "nowhere.txt"], "give the text, or --text-file"),
        (["--signature", "B"], "'B'"),
    ],
)
def test_bad_options_are_one_clear_message(tmp_path, capsys, args, says):
    rc = main(["compose", "山", "-o", str(tmp_path / "x.png"), *args, "-q"])
    err = capsys.readouterr().err
    assert rc == 2 and says in err and "Traceback" not in err


@pytest.mark.slow
def test_a_work_on_a_dask_cluster_is_the_same_sheet(tmp_path):
    pytest.importorskip("distributed")
    here, _, _, _ = compose(tmp_path, "here", "一口一")
    argv = ["compose", "一口一", "-o", str(tmp_path / "dask.png"), *SMALL]
    argv[argv.index("--workers") + 1] = "2"
    assert main([*argv, "--scheduler", "local"]) == 0
    assert np.array_equal(read_png(tmp_path / "dask.png"), here)


@pytest.mark.slow
def test_a_damaged_work_in_a_recording_is_one_clear_message(signed, tmp_path, capsys):
    _, _, rec, _ = signed
    for bad in (
        {"seal_glyphs": [{"strokes": ["M 1 2 X"]}]},
        {"seal_glyphs": "no"},
        {"layout": {"direction": "vertical"}},
    ):
        d = json.loads(rec.read_text(encoding="utf-8"))
        d["work"].update(bad)
        p = tmp_path / "bad.json"
        p.write_text(json.dumps(d), encoding="utf-8")
        t0 = time.perf_counter()
        assert main(["render", str(p), "-o", str(tmp_path / "x.png"), "-q"]) == 2
        assert time.perf_counter() - t0 < 1.0  # refused before any simulation
        err = capsys.readouterr().err
        assert "work" in err and "Traceback" not in err
