# SPDX-License-Identifier: GPL-3.0-or-later
"""Getting the extension (issue 29.10): the zip builds with plain Python, without bpy or
Blender, following blender_manifest.toml's [build] rules; the extension has one version. That
Blender's own tool validates the zip and lists the same files is checked in
tests/blender/test_install.py."""

from __future__ import annotations

import subprocess
import sys
import tomllib
import zipfile

import pytest

from tests.paths import ROOT

sys.path.insert(0, str(ROOT / "scripts"))
import build_extension  # noqa: E402

# the build script run as a user runs it, in a Python where bpy cannot be imported
NO_BPY = (
    "import runpy, sys; sys.modules['bpy'] = None; "
    "sys.argv = ['scripts/build_extension.py', sys.argv[1]]; "
    "runpy.run_path(sys.argv[0], run_name='__main__')"
)


def test_the_zip_builds_with_plain_python_where_bpy_cannot_be_imported(tmp_path):
    res = subprocess.run(
        [sys.executable, "-c", NO_BPY, str(tmp_path)],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert res.returncode == 0, res.stderr
    manifest = tomllib.loads((ROOT / "blender_manifest.toml").read_text("utf-8"))
    path = tmp_path / f"hairy_brush-{manifest['version']}.zip"
    assert res.stdout.strip() == str(path)
    names = zipfile.ZipFile(path).namelist()
    for need in ("blender_manifest.toml", "__init__.py", "sim/engine/simulation.py"):
        assert need in names
    assert "examples/strokes.json" in names and "presets/brushes/mixed.json" in names
    assert [n for n in names if n.startswith("wheels/")] == [
        w.removeprefix("./") for w in manifest["wheels"]
    ]
    for bad in ("tests/", "scripts/", "docs/", ".git", ".venv", "dist/", "pyproject.toml"):
        assert not any(n.startswith(bad) for n in names), bad
    assert not any("__pycache__" in n or n.endswith((".pyc", ".blend1")) for n in names)
    # the same checkout, the same bytes
    again = build_extension.build(tmp_path / "again")
    assert again.read_bytes() == path.read_bytes()


def test_the_exclude_patterns_follow_gitignore():
    skip = build_extension.excluded(
        ["__pycache__/", "/.git", "/docs/", "*.zip", "*.blend[1-9]", "/a/*/c.txt", "**/tmp/"]
    )
    assert skip("sim/__pycache__", True) and not skip("sim/__pycache__", False)
    assert skip(".git", True) and skip(".git", False) and not skip("sim/.git", False)
    assert skip("docs", True) and not skip("docs", False) and not skip("sim/docs", True)
    assert skip("x.zip", False) and skip("deep/er/x.zip", False) and not skip("x.zips", False)
    assert skip("a.blend1", False) and not skip("a.blend", False)
    assert skip("a/b/c.txt", False) and not skip("a/b/d/c.txt", False)
    assert skip("tmp", True) and skip("q/r/tmp", True)


def test_the_extension_has_one_version():
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text("utf-8"))
    assert "version" not in pyproject.get("project", {})
    assert "version" in tomllib.loads((ROOT / "blender_manifest.toml").read_text("utf-8"))


def test_a_manifest_naming_a_missing_wheel_gets_one_message(tmp_path):
    (tmp_path / "__init__.py").write_text("")
    (tmp_path / "blender_manifest.toml").write_text(
        'id = "x"\nversion = "1.0.0"\ntype = "add-on"\nwheels = ["./wheels/none.whl"]\n'
    )
    with pytest.raises(SystemExit, match="wheels/none.whl .* does not exist"):
        build_extension.build(tmp_path / "out", root=tmp_path)
