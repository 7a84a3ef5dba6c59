# SPDX-License-Identifier: GPL-3.0-or-later
"""Where things are, for every test: the repository and the installed extension's module."""

from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ADDON = "bl_ext.user_default.hairy_brush"  # the extension as installed from its zip
