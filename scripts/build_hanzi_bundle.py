# SPDX-License-Identifier: GPL-3.0-or-later
"""Rebuild the bundled stroke data (data/hanzi/hanzi-writer-data.bin) from the npm package
hanzi-writer-data 2.0.1: every <char>.json of the package's tarball, compact-coded and deflated
a character at a time (sim/writing/bundle.py), with the package's licence (ARPHICPL.TXT) beside
it. Every character is decoded again and compared with its source before the file is kept.

Usage: python scripts/build_hanzi_bundle.py [TARBALL] [-o OUT]
Without TARBALL it runs `npm pack hanzi-writer-data@2.0.1` in a temporary folder."""

from __future__ import annotations

import argparse
import json
import shutil
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from sim.writing.bundle import Bundle, decode, encode, write_bundle  # noqa: E402
from sim.writing.hanzi import BUNDLE, CharacterError, check_char  # noqa: E402

PACKAGE = "hanzi-writer-data"
VERSION = "2.0.1"
LICENCE = "ARPHICPL.TXT"


def npm_pack(folder: Path) -> Path:
    """The package's tarball, fetched by npm into ``folder``."""
    npm = shutil.which("npm")
    if npm is None:
        raise SystemExit("build_hanzi_bundle: npm is not installed; give the tarball instead")
    res = subprocess.run(
        [npm, "pack", f"{PACKAGE}@{VERSION}"], cwd=folder, capture_output=True, text=True
    )
    if res.returncode != 0:
        raise SystemExit(f"build_hanzi_bundle: npm pack failed:\n{res.stderr}")
    return folder / res.stdout.strip().splitlines()[-1]


def read_tarball(tarball: Path) -> tuple[dict, bytes]:
    """({character: data} of every package/<char>.json, the licence text)."""
    chars, licence = {}, None
    with tarfile.open(tarball, "r:gz") as tar:
        for member in tar:
            if not member.isfile():
                continue
            name = member.name.removeprefix("package/")
            if name == LICENCE:
                licence = tar.extractfile(member).read()
            elif "/" not in name and name.endswith(".json") and len(name) == 6:
                data = json.loads(tar.extractfile(member).read().decode("utf-8"))
                try:
                    chars[name[0]] = check_char(data, member.name)
                except CharacterError as exc:
                    print(f"skipped: {exc}", file=sys.stderr)
    if licence is None:
        raise SystemExit(f"build_hanzi_bundle: {tarball} has no package/{LICENCE}")
    return chars, licence


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("tarball", nargs="?", help=f"{PACKAGE}-{VERSION}.tgz (default: npm pack)")
    ap.add_argument("-o", "--output", default=str(BUNDLE), help="the bundle to write")
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        tarball = Path(args.tarball) if args.tarball else npm_pack(Path(tmp))
        chars, licence = read_tarball(tarball)
    if not chars:
        raise SystemExit(f"build_hanzi_bundle: no character data in {tarball}")
    for c, d in chars.items():  # the code keeps every character exactly
        if decode(encode(d)) != d:
            raise SystemExit(f"build_hanzi_bundle: {c!r} does not survive its encoding")
    out = Path(args.output)
    tmp_out = out.with_suffix(".tmp")
    size = write_bundle(tmp_out, chars)
    bundle = Bundle(tmp_out)
    t0 = time.perf_counter()
    for c, d in chars.items():
        if bundle.get(c) != d:
            raise SystemExit(f"build_hanzi_bundle: {c!r} reads back changed")
    per = (time.perf_counter() - t0) / len(chars) * 1e3
    tmp_out.replace(out)
    (out.parent / LICENCE).write_bytes(licence)
    print(f"{out}: {len(chars)} characters, {size / 2**20:.2f} MB, {per:.2f} ms a lookup")
    return 0


if __name__ == "__main__":
    sys.exit(main())
