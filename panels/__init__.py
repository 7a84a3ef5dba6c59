# SPDX-License-Identifier: GPL-3.0-or-later
"""Sidebar panels and the preset menu."""

from __future__ import annotations

import bpy

from . import presets_menu, sidebar

CLASSES = (*presets_menu.CLASSES, *sidebar.CLASSES)

register, unregister = bpy.utils.register_classes_factory(CLASSES)
