# SPDX-License-Identifier: GPL-3.0-or-later
"""Pictures read on the command line (issue 29.2): any PNG, JPEG and TIFF through Pillow (the
command line's optional dependency); without Pillow an 8-bit PNG still, anything else refused
with one message that names ``pip install pillow``."""

from __future__ import annotations

import numpy as np
import pytest

import sim.picture.ink as ink_module
from sim.picture.imitate import read_picture
from sim.picture.ink import PictureError, load_picture
from tests.picture_files import png_kinds
from tests.sim.test_picture import picture

Image = pytest.importorskip("PIL.Image")


@pytest.fixture
def files(tmp_path):
    grey = picture("王", 96)
    paths = {}
    for name, data in png_kinds(grey).items():
        paths[name] = tmp_path / f"{name}.png"
        paths[name].write_bytes(data)
    g8 = np.round(grey * 255).astype(np.uint8)
    paths["jpeg"] = tmp_path / "wang.jpg"
    Image.fromarray(g8).save(paths["jpeg"], quality=90)
    paths["tiff16"] = tmp_path / "wang16.tif"
    Image.fromarray(np.round(grey * 65535).astype(np.uint16)).save(paths["tiff16"])
    paths["tiff_rgb"] = tmp_path / "wang.tif"
    Image.fromarray(np.repeat(g8[..., None], 3, axis=2)).save(paths["tiff_rgb"])
    return grey, paths


def test_every_kind_of_picture_reads_as_the_picture(files):
    grey, paths = files
    for name, path in paths.items():
        got = load_picture(path)
        assert got.shape == grey.shape, name
        err = np.abs(got - grey)
        if name == "jpeg":  # lossy: close on the whole
            assert err.mean() < 0.02, name
        else:
            assert err.max() <= 1 / 255 + 1e-6, (name, err.max())


def test_a_16_bit_interlaced_png_is_imitated(files):
    _grey, paths = files
    im = read_picture(paths["rgba16_interlaced"], 96)
    assert len(im.strokes) == 4  # 王


def test_without_pillow_8_bit_pngs_still_read_and_the_rest_name_pillow(files, monkeypatch):
    grey, paths = files
    monkeypatch.setattr(ink_module, "_pillow", lambda: None)
    for name in ("grey8", "grey_alpha8", "palette"):
        assert np.abs(load_picture(paths[name]) - grey).max() <= 1 / 255 + 1e-6, name
    for name in ("grey16", "rgba16_interlaced", "rgb8_interlaced", "jpeg", "tiff16"):
        with pytest.raises(PictureError, match="pip install pillow"):
            load_picture(paths[name])


def test_openexr_on_the_command_line_gets_one_clear_message(tmp_path):
    exr = tmp_path / "render.exr"
    exr.write_bytes(b"\x76\x2f\x31\x01" + b"\0" * 64)
    with pytest.raises(PictureError, match="OpenEXR"):
        load_picture(exr)
