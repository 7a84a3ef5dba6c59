# SPDX-License-Identifier: GPL-3.0-or-later
"""Build the installable extension zip, dist/hairy_brush-<version>.zip, from this checkout.

    python scripts/build_extension.py [OUT_DIR]                  plain Python (3.11+), nothing else
    python scripts/build_extension.py --blender PATH [OUT_DIR]   Blender's own tool: PATH is a
                                                                 Blender executable (4.2+)
    python scripts/build_extension.py --bpy [OUT_DIR]            the tool inside the bpy module

Plain Python follows what Blender's ``extension build`` does with blender_manifest.toml: every
file of the checkout but those its ``[build] paths_exclude_pattern`` excludes (gitignore-style
patterns), the manifest and its wheels always, at the zip's top level, deflated; the zip is named
after the manifest's id and version (the extension's one version). The tests build it this way,
check that Blender's tool validates it and lists the same files, and install it. Prints the
zip's path."""

from __future__ import annotations

import argparse
import importlib.util
import os
import re
import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MANIFEST = "blender_manifest.toml"
ZIP_DATE = (2026, 1, 1, 0, 0, 0)  # every entry's date: the same checkout, the same bytes


class BuildError(SystemExit):
    """The manifest or the checkout cannot be built (the message says why)."""

    def __init__(self, message: str):
        super().__init__(f"build: {message}")


def read_manifest(root: Path = ROOT) -> dict:
    try:
        with open(root / MANIFEST, "rb") as f:
            manifest = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as exc:
        raise BuildError(f"cannot read {MANIFEST}: {exc}") from None
    for key in ("id", "version", "type"):
        if not isinstance(manifest.get(key), str) or not manifest[key]:
            raise BuildError(f"{MANIFEST} has no {key}")
    return manifest


def _glob_regex(seg: str) -> str:
    """One path segment's glob as a regex: '*' and '?' within a name, [...] a character set."""
    out, i = [], 0
    while i < len(seg):
        c = seg[i]
        if c == "*":
            out.append("[^/]*")
        elif c == "?":
            out.append("[^/]")
        elif c == "[" and "]" in seg[i + 2 :]:
            j = seg.index("]", i + 2)
            body = seg[i + 1 : j]
            out.append("[" + ("^" + body[1:] if body.startswith("!") else body) + "]")
            i = j
        else:
            out.append(re.escape(c))
        i += 1
    return "".join(out)


def _pattern_regex(pattern: str):
    """(regex, directories only) of one gitignore-style pattern over a path relative to the
    root with '/' separators: a pattern with a slash before its end is anchored at the root,
    one without matches a name at any depth; a trailing slash matches directories only; '*'
    and '?' stay within a name, '**' crosses folders."""
    if pattern.startswith("!"):
        raise BuildError(f"paths_exclude_pattern '{pattern}': negation is not supported here")
    dir_only = pattern.endswith("/")
    anchored = "/" in pattern.rstrip("/")
    segs = [s for s in pattern.strip("/").split("/") if s]
    rx = "".join("(?:.*/)?" if s == "**" else _glob_regex(s) + "/" for s in segs)
    prefix = "" if anchored else "(?:.*/)?"
    return re.compile(f"^{prefix}{rx.removesuffix('/')}$"), dir_only


def excluded(patterns: list[str]):
    """test(rel_path, is_dir) -> True when a pattern excludes it."""
    compiled = [_pattern_regex(p) for p in patterns]

    def test(rel: str, is_dir: bool) -> bool:
        return any(rx.match(rel) and (is_dir or not dir_only) for rx, dir_only in compiled)

    return test


def files_to_pack(root: Path = ROOT, manifest: dict | None = None) -> list[str]:
    """The files of the zip, relative to the root with '/' separators, sorted."""
    manifest = read_manifest(root) if manifest is None else manifest
    build = manifest.get("build", {})
    if "paths" in build:
        raise BuildError("[build] paths is not supported here: use paths_exclude_pattern")
    skip = excluded(
        build.get("paths_exclude_pattern", ["__pycache__/", ".*", "/*.zip", "*.blend[1-9]"])
    )
    out = []
    for folder, dirs, names in os.walk(root):
        rel_dir = Path(folder).relative_to(root).as_posix()
        rel_dir = "" if rel_dir == "." else rel_dir + "/"
        dirs[:] = sorted(d for d in dirs if not skip(rel_dir + d, True))
        out += [rel_dir + n for n in names if not skip(rel_dir + n, False)]
    always = [MANIFEST] + [w.removeprefix("./") for w in manifest.get("wheels", [])]
    for path in always:
        if not (root / path).is_file():
            raise BuildError(f"{path} (named by {MANIFEST}) does not exist")
    out = sorted(set(out) | set(always))
    if manifest["type"] == "add-on" and "__init__.py" not in out:
        raise BuildError("not a Python package: no __init__.py at the root")
    return out


def build(out_dir: Path, root: Path = ROOT) -> Path:
    """The zip in plain Python (see the module's docstring); returns its path."""
    manifest = read_manifest(root)
    names = files_to_pack(root, manifest)
    out_dir.mkdir(parents=True, exist_ok=True)
    path = out_dir / f"{manifest['id']}-{manifest['version']}.zip"
    tmp = path.with_name("." + path.name)
    with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED, compresslevel=9) as zf:
        for name in names:
            info = zipfile.ZipInfo(name, ZIP_DATE)
            info.external_attr = 0o644 << 16
            stored = name.endswith((".whl", ".zip", ".png", ".blend"))
            info.compress_type = zipfile.ZIP_STORED if stored else zipfile.ZIP_DEFLATED
            zf.writestr(info, (root / name).read_bytes())
    os.replace(tmp, path)
    return path


def blender_ext_tool() -> Path:
    """Blender's extension tool inside the bpy module."""
    spec = importlib.util.find_spec("bpy")
    if spec is None or not spec.submodule_search_locations:
        raise BuildError("the bpy module is not installed (run scripts/setup.sh)")
    base = Path(next(iter(spec.submodule_search_locations)))
    tools = sorted(base.glob("*/scripts/addons_core/bl_pkg/cli/blender_ext.py"))
    if not tools:
        raise BuildError(f"blender_ext.py not found under {base}")
    return tools[-1]


def build_with_tool(out_dir: Path, blender: str | None = None, root: Path = ROOT) -> Path:
    """The zip made by Blender's own tool: ``blender --command extension build`` with a
    Blender executable, else blender_ext.py from the bpy module."""
    manifest = read_manifest(root)
    out_dir.mkdir(parents=True, exist_ok=True)
    where = ["--source-dir", str(root), "--output-dir", str(out_dir)]
    if blender:
        cmd = [blender, "--factory-startup", "--command", "extension", "build", *where]
    else:
        tool = blender_ext_tool()
        subprocess.run([sys.executable, str(tool), "validate", str(root)], check=True)
        cmd = [sys.executable, str(tool), "build", *where]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    path = out_dir / f"{manifest['id']}-{manifest['version']}.zip"
    if not path.is_file():
        raise BuildError(f"Blender's tool wrote no {path.name}")
    return path


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out_dir", nargs="?", default=str(ROOT / "dist"))
    how = ap.add_mutually_exclusive_group()
    how.add_argument("--blender", metavar="PATH", help="build with this Blender executable")
    how.add_argument("--bpy", action="store_true", help="build with the bpy module's tool")
    args = ap.parse_args(argv)
    out = Path(args.out_dir)
    if args.blender or args.bpy:
        print(build_with_tool(out, args.blender))
    else:
        print(build(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
