#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The headless demo: set up .venv if needed, write calligraphy, save PNG and .blend under out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/python scripts/demo.py "$@"
