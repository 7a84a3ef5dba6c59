# SPDX-License-Identifier: GPL-3.0-or-later
import subprocess
import sys

from conftest import ROOT


def test_sim_does_not_import_blender():
    code = (
        "import sys, sim, sim.engine, sim.writing.hanzi, sim.__main__; "
        "bad = [m for m in ('bpy', 'mathutils', 'bmesh') if m in sys.modules]; "
        "print(bad); sys.exit(1 if bad else 0)"
    )
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr


def test_no_bpy_import_in_sim_sources():
    for p in (ROOT / "sim").glob("*.py"):
        text = p.read_text(encoding="utf-8")
        assert "import bpy" not in text and "from bpy" not in text, p
