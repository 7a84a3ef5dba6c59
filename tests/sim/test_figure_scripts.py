# SPDX-License-Identifier: GPL-3.0-or-later
"""The scripts that make README's pictures and the realism ranking (scripts/readme_figures.py,
scripts/realism_rank.py, scripts/revision.py): where the before/after crops are found in the
stroke data, the PNGs kept small, and the previous version exported from git."""

import numpy as np
import pytest

from scripts import readme_figures as F
from scripts import revision
from sim.writing.hanzi import find_char


def test_the_crops_of_yong_are_found_where_a_calligrapher_would_look():
    places = {k: F.to_pixels(p, 512) for k, p in F.feature_points(find_char("永")).items()}
    edge, end, turn, hook = (places[k] for k in F.FEATURES)
    assert abs(edge[1] - 253) < 16 and 150 < edge[0] < 400  # on the long vertical (竖)
    assert hook[0] > 380 and abs(hook[1] - 230) < 40  # the hook at the vertical's foot
    assert end[0] > 330 and end[1] > 420  # the 捺's foot, bottom right, written last
    assert turn[1] < 220  # a turn on the left half (the 横撇's corner)
    assert len({edge, end, turn, hook}) == 4


def test_a_character_without_a_hook_has_no_hook_crop():
    char = {"medians": [[[100, 500], [900, 500]], [[500, 800], [500, 100]]]}  # 十
    got = F.feature_points(char)
    assert got["hook"] is None and got["turn"] is None
    assert got["edge"] is not None and got["dry end"] is not None


def test_pngs_are_kept_under_the_limit(tmp_path, monkeypatch):
    pil = pytest.importorskip("PIL.Image")
    rgb = (np.random.default_rng(0).random((90, 120, 3)) * 255).astype(np.uint8)
    monkeypatch.setattr(F, "MAX_BYTES", 12_000)
    F.save_png(rgb, tmp_path / "x.png")
    assert (tmp_path / "x.png").stat().st_size <= 12_000
    assert pil.open(tmp_path / "x.png").size[0] <= 120


def test_the_previous_version_is_exported_and_a_bad_revision_named(tmp_path):
    with revision.versions(tmp_path, "HEAD") as vs:
        assert [v.name.split()[0] for v in vs] == ["new", "old"]
        assert (vs[1].root / "sim" / "__main__.py").is_file()
        assert not (vs[1].root / ".git").exists()
    with pytest.raises(SystemExit, match="not a revision"):
        with revision.versions(tmp_path / "b", "no-such-revision-xyz"):
            pass


def test_the_imitation_overlay_shows_missed_and_added_ink_in_the_ious_boxes():
    # imitate_eval --overlay (issue 26, point 4): where the imitation loses, in the square the
    # box IoU compares: ink the writing missed is red, ink it added blue; the same ink elsewhere
    # on the sheet is all black (the box forgives place and size)
    from scripts.imitate_eval import OVERLAY_SIDE, overlaid

    truth = np.zeros((200, 200), bool)
    truth[40:60, 20:180] = True  # a horizontal
    truth[40:180, 90:110] = True  # a vertical
    read = np.roll(truth, (7, -5), axis=(0, 1))  # the same ink elsewhere on the sheet
    written = truth.copy()
    written[40:60, 130:150] = False  # a piece of the horizontal missed (the box is kept)
    written[60:70, 20:60] = True  # ink added below the horizontal
    img = overlaid(truth, read, written)
    assert img.shape == (OVERLAY_SIDE, 2 * OVERLAY_SIDE + 8, 3)
    left, right = img[:, :OVERLAY_SIDE], img[:, OVERLAY_SIDE + 8 :]
    red = (right[..., 0] == 1.0) & (right[..., 2] < 0.5)
    blue = (right[..., 2] == 1.0) & (right[..., 0] < 0.5)
    assert not ((left[..., 0] == 1.0) & (left[..., 2] < 0.5)).any()  # nothing missed
    assert not ((left[..., 2] == 1.0) & (left[..., 0] < 0.5)).any()  # nor added
    assert red.any() and blue.any()


def test_a_scans_truth_follows_its_page_not_a_fixed_grey(tmp_path):
    # a character photographed on grey paper with a shadow along its foot (a copybook page
    # photographed, not scanned): read against a fixed grey the shadow is ink and sets the
    # truth's box; read against the page's own level it is paper, and the strokes stay ink.
    # A grid's line crossing the character is no ink either way
    from PIL import Image

    from scripts.imitate_scans import level_ink, scan_ink

    h, w = 240, 200
    v = np.full((h, w), 160.0)
    v[200:, :] = np.linspace(160.0, 110.0, 40)[:, None]  # the shadow: darker than 140
    v[40:60, 30:170] = 25.0  # a 横
    v[40:180, 90:110] = 25.0  # a 竖
    v[120:122, :] = 60.0  # a grid's line across the page and the 竖
    path = tmp_path / "page.png"
    Image.fromarray(np.repeat(v.astype(np.uint8)[..., None], 3, axis=2)).save(path)
    fixed, level = scan_ink(path, 140), level_ink(path, 140)
    assert fixed[225:, :].mean() > 0.5  # the shadow read as ink
    assert not level[190:, :].any() and level[45:55, 40:160].all() and level[70:170, 95:105].all()
    assert not level[118:124, :80].any() and not fixed[118:124, :80].any()  # the grid's line
