# SPDX-License-Identifier: GPL-3.0-or-later
"""A work written from text (issue 27), the engine's side, without the command line: the
restarting dip that makes each cell depend on nothing before it, the layout, the variation,
the seal and the grid, composing and rendering cells side by side bit for bit, appending text
and writing one cell again."""

from dataclasses import replace

import numpy as np
import pytest

from sim.core.recording import Dip, Recording, from_dict, loads
from sim.engine.simulation import Simulation
from sim.writing.strokes import stroke


# ------------------------------------------------------------------- the restarting dip
def _two_strokes(press_first: float):
    a = stroke([[15, 20], [45, 20]], press_mm=press_first, hair_length_mm=30)
    b = stroke([[70, 20], [100, 25]], press_mm=8.0, hair_length_mm=30)
    samples = np.concatenate([a, b])
    dips = [Dip(0, 0.7, (0, 0, 0), 0.9, restart=0), Dip(len(a), 0.7, (0, 0, 0), 0.6, restart=1)]
    rec = Recording(samples, width_mm=120, height_mm=40, px_per_mm=4.0, seed=3, dips=dips)
    return rec, len(a)


@pytest.mark.slow
def test_a_restarting_dip_makes_what_follows_independent_of_what_came_before():
    (r1, n1), (r2, _) = _two_strokes(6.0), _two_strokes(12.0)
    p1, p2 = Simulation(r1).run().paper, Simulation(r2).run().paper
    right = slice(int(60 * 4), None)  # columns of the second stroke
    assert not np.array_equal(p1.ink[:, : 60 * 4], p2.ink[:, : 60 * 4])  # the first differs
    assert p1.ink[:, right].max() > 0.3
    assert np.array_equal(p1.ink[:, right], p2.ink[:, right])  # the second does not, bit for bit
    # the second alone, from its restarting dip, on the whole paper: the same ink
    alone = replace(r1, samples=r1.samples[n1:], dips=[replace(r1.dips[1], before_sample=0)])
    assert np.array_equal(Simulation(alone).run().paper.ink[:, right], p1.ink[:, right])


def test_a_restarting_dip_is_kept_by_the_recording_and_old_ones_are_unchanged():
    rec, _ = _two_strokes(8.0)
    d = rec.to_dict()
    assert d["dips"][1]["restart"] == 1
    back = from_dict(d)
    assert [dp.restart for dp in back.dips] == [0, 1]
    plain = Dip(5, 0.5)
    assert "restart" not in plain.to_dict() and plain.restart is None
    d["dips"][1]["restart"] = -1
    with pytest.raises(ValueError, match="restart"):
        loads(__import__("json").dumps(d))


# ------------------------------------------------------------------------------- the text
def test_punctuation_is_left_out_or_kept_and_a_newline_starts_a_line():
    from sim.writing.work.text import CHAR, MARK, SPACE, parse_text

    lines = parse_text("床前，明月。\n疑是　地上\n\n")
    assert [[g.text for g in line] for line in lines] == [list("床前明月"), list("疑是 地上")]
    assert lines[1][2].kind == SPACE
    kept = parse_text("床前，明月。", punctuation="keep")[0]
    assert [g.kind for g in kept] == [CHAR, CHAR, MARK, CHAR, CHAR, MARK]


def test_characters_without_stroke_data_are_named_each_once():
    from sim.writing.work.text import MissingCharacters, missing_characters, parse_text

    lines = parse_text("山A水😀xA山")
    missing = missing_characters(lines)
    assert missing == ["A", "😀", "x"]
    msg = str(MissingCharacters(missing))
    for c in ("'A'", "'😀'", "'x'", "LATIN CAPITAL LETTER A", "--skip-missing"):
        assert c in msg
    assert missing_characters(parse_text("，。「」", punctuation="keep")) == []


# ------------------------------------------------------------------------------ the layout
def _lines(text):
    from sim.writing.work.text import parse_text

    return parse_text(text)


def test_a_vertical_work_reads_in_columns_from_the_right_evenly_spaced():
    from sim.writing.work.layout import SIGNATURE, TEXT, Settings, lay_out

    lay = lay_out(
        _lines("一口小大山水天日月"),
        Settings(per_line=3, char_mm=50.0, signature="王羲", seal="王"),
    )
    text = [c for c in lay.cells if c.role == TEXT]
    assert [c.char for c in text] == list("一口小大山水天日月")
    assert {c.size for c in text} == {50.0}  # one em box: 一 and 口 keep their own extent
    xs = sorted({round(c.x, 6) for c in text}, reverse=True)
    assert [c.x for c in text[:3]] == [xs[0]] * 3 and text[3].x == xs[1]  # right column first
    assert np.allclose(np.diff(xs), np.diff(xs)[0])  # columns evenly spaced
    ys = [c.y for c in text[:3]]
    assert ys[0] > ys[1] > ys[2] and np.isclose(ys[0] - ys[1], ys[1] - ys[2])  # top to bottom
    sig = [c for c in lay.cells if c.role == SIGNATURE]
    assert [c.char for c in sig] == ["王", "羲"] and all(c.size < 50.0 for c in sig)
    assert all(c.x + c.size < min(xs) for c in sig)  # its own column, left of the text
    assert sig[0].y + sig[0].size < text[0].y + text[0].size  # starting lower than the text
    x0, y0, x1, y1 = lay.seal["box"]
    assert y1 < sig[-1].y and x0 < sig[-1].x + sig[-1].size and x1 > sig[-1].x  # under it
    for c in lay.cells:  # everything on the paper, inside a margin
        assert 20 < c.x and c.x + c.size < lay.width_mm - 20
        assert 20 < c.y and c.y + c.size < lay.height_mm - 20


def test_a_horizontal_work_reads_in_rows_and_signs_under_them():
    from sim.writing.work.layout import SIGNATURE, TEXT, Settings, lay_out

    lay = lay_out(_lines("山水\n日月天"), Settings("horizontal", char_mm=40.0, signature="人"))
    text = [c for c in lay.cells if c.role == TEXT]
    assert [(c.char, c.line, c.index) for c in text] == [
        ("山", 0, 0),
        ("水", 0, 1),
        ("日", 1, 0),
        ("月", 1, 1),
        ("天", 1, 2),
    ]
    assert text[0].y == text[1].y > text[2].y and text[0].x < text[1].x
    (sig,) = [c for c in lay.cells if c.role == SIGNATURE]
    assert sig.y + sig.size < text[2].y and sig.x + sig.size <= text[4].x + 40.0 + 1e-6


def test_a_paper_of_a_given_size_is_filled_within_its_margins():
    from sim.writing.work.layout import PAPER_MARGIN, Settings, lay_out, paper_size

    a4 = paper_size("A4", landscape=False)
    lay = lay_out(
        _lines("床前明月光疑是地上霜举头望明月低头思故乡"),
        Settings(paper_mm=a4, signature="李白", seal="太白"),
    )
    assert (lay.width_mm, lay.height_mm) == (210.0, 297.0)
    margin = PAPER_MARGIN * 210.0
    boxes = [c.box() for c in lay.cells] + [tuple(lay.seal["box"])]
    lo = np.min([b[:2] for b in boxes], axis=0)
    hi = np.max([b[2:] for b in boxes], axis=0)
    assert np.all(lo >= margin - 1e-6) and hi[0] <= 210 - margin + 1e-6
    assert hi[1] <= 297 - margin + 1e-6
    assert max(hi[0] - lo[0], hi[1] - lo[1]) > 0.85 * (297 - 2 * margin) * 0.6  # it is filled
    assert paper_size("a3", landscape=True) == (420.0, 297.0)
    assert paper_size("300x200", False) == (300.0, 200.0)
    with pytest.raises(ValueError, match="unknown paper"):
        paper_size("letterish", False)


def test_the_number_of_characters_a_line_balances_the_block():
    from sim.writing.work.layout import auto_per_line

    assert auto_per_line(_lines("床前明月光疑是地上霜举头望明月低头思故乡"), True) == 5
    assert auto_per_line(_lines("山水\n日月天"), True) == 3  # the text's own lines


def test_the_layout_goes_into_the_recording_and_comes_back():
    from sim.writing.work.layout import Layout, Settings, lay_out

    lay = lay_out(_lines("山水，日月"), Settings(char_mm=30.0, seal="王", grid="tian"))
    back = Layout.from_dict(__import__("json").loads(__import__("json").dumps(lay.to_dict())))
    assert back == lay
    assert back.next_place() == (lay.cells[-1].line + 1, 0) or back.next_place()[1] > 0
    with pytest.raises(ValueError, match="work.layout"):
        Layout.from_dict({**lay.to_dict(), "direction": "diagonal"})


# --------------------------------------------------------------------- a work, composed
def _template(seed=5):
    return Recording(np.zeros((1, 6)), seed=seed)


@pytest.fixture(scope="module")
def tiny():
    """一口一 in a column with a signature and a seal, small (24 mm, 40 px an em box), one
    practice pass: (recording, layout)."""
    from sim.writing.work.compose import Options, compose
    from sim.writing.work.layout import Settings

    settings = Settings(char_mm=24.0, signature="人", seal="永", grid="mi")
    rec, lay, skipped = compose(
        "一口一", settings, _template(), char_px=40.0, options=Options(passes=1)
    )
    assert skipped == []
    return rec, lay


@pytest.mark.slow
def test_cells_rendered_side_by_side_in_processes_equal_one_run(tiny):
    from concurrent.futures import ProcessPoolExecutor

    from sim.writing.work.compose import image8, render

    def pool(fn, tasks, done=None):
        with ProcessPoolExecutor(2) as ex:
            return list(ex.map(fn, tasks))

    rec, lay = tiny
    paper, inks = render(rec, mapper=pool)
    one = Simulation(rec).run().paper
    assert np.array_equal(paper.ink, one.ink) and np.array_equal(paper.wet, one.wet)
    assert np.array_equal(paper.last, one.last)
    assert np.array_equal(image8(paper, rec), image8(one, rec))
    assert len(inks) == len(lay.cells) and all(ci.mask.any() for ci in inks)


@pytest.mark.slow
def test_one_brush_dips_first_and_when_its_ink_runs_low(tiny):
    from sim.writing.work.compose import LOW_INK, assemble

    rec, lay = tiny
    starts = {c.samples[0] for c in lay.cells}
    restarting = [dp for dp in rec.dips if dp.restart is not None]
    assert [dp.before_sample for dp in restarting] == [c.samples[0] for c in lay.cells]
    for dp in rec.dips:  # the other dips are the writer's own, inside a character
        if dp.restart is None:
            assert dp.before_sample not in starts
            assert any(c.samples[0] < dp.before_sample < c.samples[1] for c in lay.cells)
    assert lay.cells[0].dip and lay.cells[0].load == 1.0
    for a, b in zip(lay.cells, lay.cells[1:], strict=False):
        assert b.samples[0] == a.samples[1]  # one recording, the cells in writing order
        if b.dip:
            assert b.load == 1.0
        else:
            assert np.isclose(b.load, a.load - a.used)
    wet = [dp.wetness for dp in restarting]
    assert wet[0] == max(wet)

    def written(used, dips=()):
        return type("W", (), {"samples": np.zeros((3, 6)), "used": used, "dips": dips})()

    # --dip-every 2: a dip before every other character, each with a full load
    w = [written(0.4) for _ in range(4)]
    cells = [replace(c) for c in lay.cells[:3]] + [replace(lay.cells[0])]
    _, dips, _ = assemble(rec, cells, w, 0.5, dip_every=2)
    assert [c.dip for c in cells] == [True, False, True, False]
    assert cells[1].load == pytest.approx(0.6) and cells[3].load == pytest.approx(0.6)
    # when the ink runs low: dipped before a character that would end below LOW_INK; one
    # that dips inside itself gets those dips and leaves the brush as its last dip did
    w = [written(0.3), written(0.2), written(0.2, dips=(1,)), written(0.1)]
    cells = [replace(c) for c in lay.cells[:3]] + [replace(lay.cells[0])]
    samples, dips, load = assemble(rec, cells, w, 0.5)
    assert 1.0 - 0.3 - 0.2 < LOW_INK and [c.dip for c in cells] == [True, True, False, False]
    a, b = cells[2].samples
    inner = [dp for dp in dips if dp.restart is None]
    assert len(inner) == 1 and a < inner[0].before_sample < b
    assert inner[0].before_sample == b - 3 + 1  # its sample 1, after the travel to the cell
    assert cells[3].load == pytest.approx(0.8) and load == pytest.approx(0.7)


@pytest.mark.slow
def test_a_character_written_twice_is_not_a_copy(tiny):
    rec, lay = tiny
    one, _, again = lay.cells[:3]
    assert one.char == again.char == "一" and one.variation != again.variation
    a = rec.samples[one.samples[0] : one.samples[1]] - [one.x, one.y, 0, 0, 0, 0]
    b = rec.samples[again.samples[0] : again.samples[1]] - [again.x, again.y, 0, 0, 0, 0]
    a, b = a[a[:, 2] < 30], b[b[:, 2] < 30]  # where the brush writes (not the travel)
    assert len(a) != len(b) or not np.allclose(a, b, atol=0.05)


@pytest.mark.slow
def test_the_layout_items_hold_each_characters_ink(tiny):
    from sim.writing.work.compose import INK_SEEN, layout_items, render

    rec, lay = tiny
    paper, inks = render(rec)
    items = layout_items(rec, inks)["items"]
    assert [(i["char"], i["role"]) for i in items] == [
        ("一", "text"),
        ("口", "text"),
        ("一", "text"),
        ("人", "signature"),
        ("永", "seal"),
    ]
    H = rec.height_px
    for item, ci in zip(items[:-1], inks, strict=True):  # the cells are in reading order
        x0, y0, x1, y1 = item["box"]
        # ink that shows (the wick's faintest fringe is below that)
        rows, cols = np.nonzero(ci.mask & (ci.ink.max(axis=-1) > INK_SEEN))
        assert rows.size, item
        r0, _, c0, _ = ci.window
        img_rows = H - 1 - (r0 + rows)
        assert cols.min() + c0 >= x0 and cols.max() + c0 < x1, item
        assert img_rows.min() >= y0 and img_rows.max() < y1, item


@pytest.mark.slow
def test_text_appended_goes_on_after_the_last_character_on_the_same_paper(tiny):
    from sim.writing.work.compose import Options, compose, render
    from sim.writing.work.edit import append_text
    from sim.writing.work.layout import Layout, Settings

    rec, _, _ = compose(
        "山",
        Settings(char_mm=24.0, per_line=2, paper_mm=(150.0, 90.0)),
        _template(),
        char_px=40.0,
        options=Options(passes=1),
    )
    more, cells = append_text(rec, "一\n口", options=Options(passes=1))
    assert (more.width_mm, more.height_mm, more.px_per_mm) == (
        rec.width_mm,
        rec.height_mm,
        rec.px_per_mm,
    )
    n = len(rec.samples)
    assert np.array_equal(more.samples[:n], rec.samples) and more.dips[: len(rec.dips)] == rec.dips
    lay = Layout.from_dict(more.extra["work"]["layout"])
    assert [(c.char, c.line, c.index) for c in lay.cells] == [
        ("山", 0, 0),
        ("一", 0, 1),
        ("口", 1, 0),
    ]
    assert [c.samples[0] for c in cells][0] == n
    before, after = render(rec)[0], render(more)[0]
    assert np.array_equal(before.ink, np.where(_owned(after, more, [0]), after.ink, 0))


def _owned(paper, rec, which):
    """(H, W, 1) bool: the pixels the cells ``which`` of the work touched."""
    from sim.writing.work.compose import cell_recording, render_cell
    from sim.writing.work.layout import Layout

    lay = Layout.from_dict(rec.extra["work"]["layout"])
    out = np.zeros((paper.H, paper.W, 1), dtype=bool)
    for k in which:
        ci = render_cell(cell_recording(rec, lay.cells[k]))
        r0, r1, c0, c1 = ci.window
        out[r0:r1, c0:c1, 0] |= ci.mask
    return out


@pytest.mark.slow
def test_one_cell_written_again_leaves_the_others_untouched(tiny):
    from sim.writing.work.compose import Options, render
    from sim.writing.work.edit import rewrite_cell
    from sim.writing.work.layout import Layout

    rec, lay = tiny
    again = rewrite_cell(rec, 1, seed=99, options=Options(passes=1))
    new = Layout.from_dict(again.extra["work"]["layout"])
    assert new.cells[1].seed == 99 and new.cells[1].variation != lay.cells[1].variation
    a, b = lay.cells[1].samples
    assert np.array_equal(again.samples[:a], rec.samples[:a])
    shift = new.cells[2].samples[0] - lay.cells[2].samples[0]
    assert np.array_equal(again.samples[b + shift :], rec.samples[b:])
    p0, p1 = render(rec)[0], render(again)[0]
    mine = _owned(p0, rec, [1]) | _owned(p1, again, [1])
    assert np.array_equal(np.where(mine, 0, p0.ink), np.where(mine, 0, p1.ink))  # the others
    assert not np.array_equal(p0.ink, p1.ink)  # and the cell itself changed


def test_a_short_text_is_one_line():
    from sim.writing.work.layout import auto_per_line

    assert auto_per_line(_lines("山，水"), False) == 2
    assert auto_per_line(_lines("山水日"), False) == 3


@pytest.mark.slow
def test_a_work_written_in_calls_is_signed_after_its_text(tiny):
    from sim.writing.work.compose import Options, compose
    from sim.writing.work.edit import append_text, sign_work
    from sim.writing.work.layout import SIGNATURE, Layout, Settings

    one = Options(passes=1)
    rec, _, _ = compose(
        "山",
        Settings(char_mm=24.0, per_line=2, paper_mm=(150.0, 90.0)),
        _template(),
        char_px=40.0,
        options=one,
    )
    rec, _ = append_text(rec, "水", options=one)
    signed = sign_work(rec, "人", "永", options=one)
    n = len(rec.samples)
    assert np.array_equal(signed.samples[:n], rec.samples)
    lay = Layout.from_dict(signed.extra["work"]["layout"])
    (sig,) = [c for c in lay.cells if c.role == SIGNATURE]
    assert sig.samples[0] == n and sig.x + sig.size < min(c.x for c in lay.cells[:2])
    assert lay.seal["text"] == "永" and signed.extra["work"]["seal_glyphs"]
    with pytest.raises(ValueError, match="signed"):
        append_text(signed, "大", options=one)
