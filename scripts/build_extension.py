# SPDX-License-Identifier: GPL-3.0-or-later
"""Validate blender_manifest.toml and build the installable extension zip with Blender's own
extension tool (it ships inside the bpy wheel). Usage: python scripts/build_extension.py [OUT_DIR]
Prints the zip's path."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def blender_ext_tool() -> Path:
    spec = importlib.util.find_spec("bpy")
    if spec is None or not spec.submodule_search_locations:
        raise SystemExit("build: the bpy module is not installed (run scripts/setup.sh)")
    base = Path(next(iter(spec.submodule_search_locations)))
    tools = sorted(base.glob("*/scripts/addons_core/bl_pkg/cli/blender_ext.py"))
    if not tools:
        raise SystemExit(f"build: blender_ext.py not found under {base}")
    return tools[-1]


def build(out_dir: Path) -> Path:
    tool = blender_ext_tool()
    out_dir.mkdir(parents=True, exist_ok=True)
    subprocess.run([sys.executable, str(tool), "validate", str(ROOT)], check=True)
    subprocess.run(
        [
            sys.executable,
            str(tool),
            "build",
            "--source-dir",
            str(ROOT),
            "--output-dir",
            str(out_dir),
        ],
        check=True,
        stdout=subprocess.DEVNULL,
    )
    zips = sorted(out_dir.glob("hairy_brush-*.zip"), key=lambda p: p.stat().st_mtime)
    if not zips:
        raise SystemExit("build: no zip was written")
    return zips[-1]


if __name__ == "__main__":
    print(build(Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "dist"))
