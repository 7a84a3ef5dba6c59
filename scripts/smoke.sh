#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The smoke test (scripts/smoke.py: install the zip, write, simulate, render, save, reopen, exit
# cleanly) on each Blender LTS the manifest promises, through its bpy module in its own venv,
# .venv-bpy42 and .venv-bpy45 (made the first time, about 400 MB each; kept afterwards).
#   bash scripts/smoke.sh                 4.2.23 and 4.5.15
#   bash scripts/smoke.sh 4.2.23 ...      the given bpy versions
#   bash scripts/smoke.sh --drop ...      each venv removed after its run (CI: a clean clone makes
#                                         them anyway, and the two need not be on disk at once)
# pip keeps no copy of the wheels (--no-cache-dir): a bpy wheel is about 300 MB.
set -euo pipefail
cd "$(dirname "$0")/.."
drop=0
if [ "${1:-}" = "--drop" ]; then
  drop=1
  shift
fi
pick_python() {
  for c in "${PYTHON:-}" python3.11 python3; do
    [ -n "$c" ] || continue
    if command -v "$c" >/dev/null 2>&1 && "$c" -c 'import sys; sys.exit(sys.version_info[:2] != (3, 11))'; then
      echo "$c"; return 0
    fi
  done
  return 1
}
[ $# -gt 0 ] || set -- 4.2.23 4.5.15
failed=()
for version in "$@"; do
  IFS=. read -r major minor _ <<<"$version"
  venv=".venv-bpy${major}${minor}"
  stamp="$venv/.installed-bpy-$version"
  if [ ! -f "$stamp" ]; then
    PY=$(pick_python) || { echo "smoke: Python 3.11 is required (bpy is built for it); set PYTHON=/path/to/python3.11" >&2; exit 1; }
    echo "smoke: making $venv with bpy==$version (the first time only)" >&2
    rm -rf "$venv"
    "$PY" -m venv "$venv"
    # numpy 1.26, as Blender 4.2 and 4.5 ship it
    "$venv/bin/python" -m pip install --quiet --no-cache-dir "bpy==$version" "numpy>=1.24,<2"
    touch "$stamp"
  fi
  if ! "$venv/bin/python" scripts/smoke.py; then
    failed+=("$version")
  fi
  if [ "$drop" = 1 ]; then
    rm -rf "$venv"
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "smoke: FAILED on bpy ${failed[*]}" >&2
  exit 1
fi
