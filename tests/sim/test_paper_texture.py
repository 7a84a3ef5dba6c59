# SPDX-License-Identifier: GPL-3.0-or-later
"""The sheet's own look (issue 26): xuan paper's clouds and fibres under and between the ink
(``sim.paper.texture``), the same in every window, tile, band and print. No Blender."""

import numpy as np

from sim.image.png import to_uint8
from sim.image.prints import print_image
from sim.paper.display import PaperView
from sim.paper.paper import Paper
from sim.paper.texture import paper_tone, sheet_tone


def test_the_tone_is_the_same_in_any_window_and_for_the_same_sheet_only():
    whole = paper_tone(slice(0, 90), slice(0, 120), 5.0, 0.05, seed=3)
    part = paper_tone(slice(31, 77), slice(50, 119), 5.0, 0.05, seed=3)
    assert np.array_equal(whole[31:77, 50:119], part)  # a tile is the sheet's, bit for bit
    kept = sheet_tone(slice(31, 77), slice(50, 119), 5.0, 0.05, 3, tile=16)  # from kept tiles
    assert np.array_equal(kept, part) and np.array_equal(
        sheet_tone(slice(31, 77), slice(50, 119), 5.0, 0.05, 3, tile=16), part
    )
    assert np.array_equal(whole, paper_tone(slice(0, 90), slice(0, 120), 5.0, 0.05, seed=3))
    other = paper_tone(slice(0, 90), slice(0, 120), 5.0, 0.05, seed=4)
    assert np.abs(other - whole).mean() > 0.003  # another seed, another sheet
    flat = paper_tone(slice(0, 90), slice(0, 120), 5.0, 0.0, seed=3)
    assert flat.dtype == np.float32 and np.all(flat == 1.0)


def test_the_clouds_and_fibres_keep_their_size_in_millimetres(monkeypatch):
    # the same 60 mm of sheet at 4 and at 12 px/mm: the tone averaged over 2 mm cells agrees
    # (the clouds, several mm across, are the same clouds), and it varies by a few per cent
    lo = paper_tone(slice(0, 240), slice(0, 240), 4.0, 0.05, seed=1)
    hi = paper_tone(slice(0, 720), slice(0, 720), 12.0, 0.05, seed=1)
    cells_lo = lo.reshape(30, 8, 30, 8).mean(axis=(1, 3))
    cells_hi = hi.reshape(30, 24, 30, 24).mean(axis=(1, 3))
    assert np.corrcoef(cells_lo.ravel(), cells_hi.ravel())[0, 1] > 0.9
    for t in (lo, hi):
        assert 0.004 < t.std() < 0.02 and 0.9 < t.min() and t.max() < 1.1
    # a fibre is far finer than a cloud: with the fibres the tone changes much more from
    # pixel to pixel than the clouds alone make it (the smallest are 1.6 mm across)
    import sim.paper.texture as texture

    monkeypatch.setattr(texture, "THREADS", 0.0)
    clouds = paper_tone(slice(0, 720), slice(0, 720), 12.0, 0.05, seed=1)
    assert np.abs(np.diff(hi, axis=1)).mean() > 3.0 * np.abs(np.diff(clouds, axis=1)).mean()


def _inked(texture: float) -> Paper:
    paper = Paper(150, 110, 4.0, color=(0.95, 0.93, 0.87), texture=texture, grain_seed=5)
    paper.ink[40:70, 30:120] = 0.8  # a band of ink
    paper._touch(40, 70, 30, 120)
    return paper


def test_every_view_of_the_paper_shows_the_same_sheet():
    paper = _inked(0.05)
    rgb = paper.rgb()
    # the ink darkens the sheet it lies on; the bare sheet is the colour with its texture
    sheet = paper.sheet(slice(0, paper.H), slice(0, paper.W))
    np.testing.assert_allclose(rgb, sheet * (1.0 - np.clip(paper.ink, 0, 1)), rtol=1e-6)
    assert sheet[:30].std(axis=(0, 1)).min() > 0.002
    assert np.array_equal(paper.rgb8(chunk_rows=17), to_uint8(rgb[::-1]))  # bands, any size
    view = PaperView(linear=False)
    view.refresh(paper)  # the Blender image: the blank sheet, then the tiles that changed
    np.testing.assert_allclose(view.pixels[..., :3], rgb, atol=1e-6)
    flat = _inked(0.0)  # no texture: the flat colour, as before
    assert np.all(flat.rgb()[:30] == np.float32([0.95, 0.93, 0.87]))


def test_a_print_shows_the_sheet_at_its_own_resolution():
    paper = _inked(0.05)
    big = print_image(paper, 450, 330).astype(float) / 255  # 3x the paper's pixels
    small = paper.rgb8().astype(float) / 255
    bare_big, bare_small = big[-60:], small[-20:]  # below the ink band: bare sheet
    np.testing.assert_allclose(bare_big.mean(axis=(0, 1)), bare_small.mean(axis=(0, 1)), atol=0.01)
    assert bare_big[..., 1].std() > 0.002  # its clouds and fibres, not a flat colour
    matte = print_image(paper, 450, 330, matte=True)
    assert np.all(matte[-60:, :, 3] == 0)  # the ink's matte carries no paper


def test_kept_tiles_are_read_back_by_a_new_process_and_made_again_when_spoilt(tmp_path):
    """issue 28: the tiles of tone are kept in the cache folder; a new process (the memory's
    tiles forgotten) reads them back, the same values, and a spoilt file is made again."""
    from sim.paper import texture

    window = (slice(31, 77), slice(50, 119), 5.0, 0.05, 3)
    plain = paper_tone(*window)
    try:
        texture.keep_tiles_in(tmp_path)
        texture._tile_tone.cache_clear()
        first = sheet_tone(*window, tile=16)
        files = sorted(tmp_path.rglob("*.npy"))
        assert len(files) == 4 * 5  # the window's tiles, every one kept
        texture._tile_tone.cache_clear()  # as a new process
        files[0].write_bytes(b"not a tile")
        again = sheet_tone(*window, tile=16)
        assert np.load(files[0]).shape == (16, 16)  # made again
    finally:
        texture.keep_tiles_in(None)
        texture._tile_tone.cache_clear()
    assert first.tobytes() == plain.tobytes() == again.tobytes()


def test_the_draw_from_kept_tiles_is_the_draw_of_the_windows_tone():
    from sim.paper.texture import DRAW_BASE, DRAW_MIN, DRAW_SPREAD, sheet_draw

    tone = paper_tone(slice(3, 70), slice(20, 41), 6.0, 1.0, 5)
    want = np.clip(DRAW_BASE + DRAW_SPREAD * 0.62 * (tone - 1.0), DRAW_MIN, 1.0)
    got = sheet_draw(slice(3, 70), slice(20, 41), 6.0, 5, 16, 0.62)
    assert got.dtype == np.float32 and got.tobytes() == want.astype(np.float32).tobytes()


def test_the_kept_tiles_are_bounded_oldest_first_over_every_version(tmp_path):
    """A cache that only grows fills a user's disk: when a command starts, the oldest kept tiles
    of every version's folder go first, down to the bound, and an emptied folder goes too."""
    import os

    from sim.paper import texture

    old, new = tmp_path / "paper-tone-0000", tmp_path / "paper-tone-1111"
    for folder, count, start in ((old, 3, 0), (new, 4, 100)):
        folder.mkdir()
        for k in range(count):
            path = folder / f"{k}.npy"
            np.save(path, np.zeros((2, 2), np.float32))
            os.utime(path, ns=((start + k) * 10**9, (start + k) * 10**9))
    (tmp_path / "response-x.json").write_text("{}")  # not a tile: never touched
    texture._prune_kept_tiles(tmp_path, 2)
    assert not old.exists()  # every tile in it older than the newest two
    assert sorted(p.name for p in new.iterdir()) == ["2.npy", "3.npy"]
    assert (tmp_path / "response-x.json").exists()
    texture._prune_kept_tiles(tmp_path, 5)  # under the bound: nothing goes
    assert len(list(new.iterdir())) == 2
