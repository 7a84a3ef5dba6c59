# SPDX-License-Identifier: GPL-3.0-or-later
"""The bundled stroke data travels inside the extension's zip (issue 27, point 1)."""

import zipfile

from sim.writing.hanzi import BUNDLE


def test_the_zip_holds_the_bundle_and_its_licence(extension_zip):
    z = zipfile.ZipFile(extension_zip)
    names = z.namelist()
    for name in ("data/hanzi/hanzi-writer-data.bin", "data/hanzi/ARPHICPL.TXT"):
        assert name in names, name
    info = z.getinfo("data/hanzi/hanzi-writer-data.bin")
    assert info.file_size == BUNDLE.stat().st_size
    assert info.compress_size <= 15 * 2**20  # issue 27: at most 15 MB added to the zip
    assert z.read("data/hanzi/hanzi-writer-data.bin") == BUNDLE.read_bytes()
