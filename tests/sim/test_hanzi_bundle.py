# SPDX-License-Identifier: GPL-3.0-or-later
"""The bundled stroke data (issue 27, point 1): all of hanzi-writer-data 2.0.1 in the extension,
read lazily, rebuilt by scripts/build_hanzi_bundle.py; the user's own data wins."""

import io
import json
import subprocess
import sys
import tarfile

import pytest

from sim.writing import bundle as bundle_mod
from sim.writing import hanzi
from sim.writing.bundle import Bundle, decode, encode, write_bundle
from sim.writing.hanzi import BUNDLE, CharacterError, find_char, lookup
from tests.paths import ROOT

SHIPPED = sorted((ROOT / "data" / "hanzi").glob("*.json"))
UNSEEN = sorted((ROOT / "tests" / "data" / "unseen").glob("*.json"))


def source(path):
    return json.loads(path.read_text(encoding="utf-8"))


def test_the_bundle_holds_every_character_and_the_shipped_files_exactly():
    b = Bundle(BUNDLE)
    assert len(b) == 9574
    chars = b.characters()
    assert "永" in chars and "龍" in chars and "龙" in chars  # simplified and traditional
    assert (
        (BUNDLE.parent / "ARPHICPL.TXT")
        .read_text(encoding="utf-8")
        .startswith("ARPHIC PUBLIC LICENSE")
    )
    for path in SHIPPED + UNSEEN:  # the package's own files, byte for byte the same values
        assert find_char(path.stem) == source(path), path.name
        assert b.get(path.stem) == source(path), path.name


def test_a_lookup_decodes_one_record_not_the_set(monkeypatch):
    calls = []
    real = bundle_mod.decode
    monkeypatch.setattr(bundle_mod, "decode", lambda rec: calls.append(1) or real(rec))
    b = Bundle(BUNDLE)
    assert b.get("鬱")["strokes"] and len(calls) == 1
    assert b.get("A") is None and b.get("。") is None and len(calls) == 1
    assert "鬱" in b and "ab" not in b


def test_the_code_keeps_odd_data_exactly():
    odd = [
        {"strokes": ["M 1 2 L 3 4 Z"], "medians": [[[1, 2]]]},  # no radStrokes
        {"strokes": ["M 1.5 2 L 3 4 Z"], "medians": [[[1, 2], [3, 4]]]},  # a fraction
        {"strokes": ["M 1 2  L 3 4 Z"], "medians": [[[1, 2]]], "radStrokes": [0]},  # spacing
        {"strokes": ["M 1 2 C 3 4 5 6 7 -8 Q 9 10 11 12 Z"], "medians": [[[1.5, 2]]]},
        {"strokes": ["M 1 2 Z"], "medians": [[[-300, 2000]]], "radStrokes": [0, 5]},
    ]
    for d in odd:
        assert decode(encode(d)) == d
    assert encode(odd[0])[0] == bundle_mod.COMPACT and encode(odd[1])[0] == bundle_mod.JSON_TEXT


def test_a_damaged_bundle_is_named(tmp_path):
    p = tmp_path / "b.bin"
    p.write_bytes(b"not a bundle at all")
    with pytest.raises(bundle_mod.BundleError, match="not a stroke data bundle"):
        Bundle(p).get("永")
    write_bundle(p, {"一": source(SHIPPED[0])})
    p.write_bytes(p.read_bytes()[:12])
    with pytest.raises(bundle_mod.BundleError, match="truncated"):
        Bundle(p).get("一")


def _tarball(path, chars: dict, licence=b"ARPHIC PUBLIC LICENSE\n"):
    with tarfile.open(path, "w:gz") as tar:
        for name, data in [("package/ARPHICPL.TXT", licence), ("package/package.json", b"{}")] + [
            (f"package/{c}.json", json.dumps(d, ensure_ascii=False).encode())
            for c, d in chars.items()
        ]:
            info = tarfile.TarInfo(name)
            info.size = len(data)
            tar.addfile(info, io.BytesIO(data))


def test_the_script_rebuilds_the_bundle_from_the_package(tmp_path):
    chars = {p.stem: source(p) for p in SHIPPED[:5]}
    tgz = tmp_path / "hanzi-writer-data-2.0.1.tgz"
    _tarball(tgz, chars)
    out = tmp_path / "out" / "bundle.bin"
    out.parent.mkdir()
    script = ROOT / "scripts" / "build_hanzi_bundle.py"
    res = subprocess.run(
        [sys.executable, str(script), str(tgz), "-o", str(out)], capture_output=True, text=True
    )
    assert res.returncode == 0, res.stderr
    assert "5 characters" in res.stdout
    b = Bundle(out)
    assert b.characters() == "".join(sorted(chars, key=ord))
    assert all(b.get(c) == d for c, d in chars.items())
    assert (out.parent / "ARPHICPL.TXT").read_bytes() == b"ARPHIC PUBLIC LICENSE\n"


def test_the_users_data_wins_over_the_bundle(tmp_path):
    yong = source(ROOT / "data" / "hanzi" / "永.json")
    mine = {"strokes": yong["strokes"][:2], "medians": yong["medians"][:2]}
    folder = tmp_path / "mine"
    folder.mkdir()
    (folder / "永.json").write_text(json.dumps(mine), encoding="utf-8")
    assert find_char("永", folder) == mine
    assert find_char("龍", folder) == Bundle(BUNDLE).get("龍")  # not in the folder: the bundle
    g = tmp_path / "graphics.txt"
    lines = [{"character": "大", **mine}, {"character": "永", **mine}]
    g.write_text("\n".join(json.dumps(x, ensure_ascii=False) for x in lines), encoding="utf-8")
    assert find_char("永", g) == {"character": "永", **mine}
    assert find_char("山", g) == source(ROOT / "data" / "hanzi" / "山.json")
    assert lookup("A", g) is None and lookup("😀") is None
    with pytest.raises(CharacterError, match="no data for 'A'"):
        find_char("A", folder)
    with pytest.raises(CharacterError, match="does not exist"):
        find_char("永", tmp_path / "nowhere")


def test_graphics_txt_is_indexed_once(tmp_path, monkeypatch):
    g = tmp_path / "graphics.txt"
    rows = [{"character": p.stem, **source(p)} for p in SHIPPED]
    g.write_text("\n".join(json.dumps(r, ensure_ascii=False) for r in rows), encoding="utf-8")
    opened = []
    real_open = open
    monkeypatch.setattr(
        "builtins.open", lambda f, *a, **k: opened.append(str(f)) or real_open(f, *a, **k)
    )
    for r in rows:
        assert find_char(r["character"], g) == r
    # one pass over the file for the index, then one read of a line per character
    assert opened.count(str(g)) == len(rows) + 1
    assert hanzi._graphics_index(g)["永"][0] == [r["character"] for r in rows].index("永") + 1
