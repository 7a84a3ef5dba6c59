#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The test command: set up .venv if needed, lint, run the test suite (what CI runs).
#   bash scripts/test.sh            everything
#   bash scripts/test.sh --fast     lint and the tests not marked slow (under a minute)
#   bash scripts/test.sh ARGS...    lint, then pytest with ARGS (e.g. tests/sim -k paper)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/python -m ruff check .
.venv/bin/python -m ruff format --check .
if [ "${1:-}" = "--fast" ]; then
  shift
  set -- -m "not slow" "$@"
fi
.venv/bin/python -m pytest "$@"
