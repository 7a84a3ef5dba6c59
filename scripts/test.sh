#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The test command: set up .venv if needed, lint, run the test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/python -m ruff check .
.venv/bin/python -m ruff format --check .
.venv/bin/python -m pytest "$@"
