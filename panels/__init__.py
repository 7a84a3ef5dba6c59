# SPDX-License-Identifier: GPL-3.0-or-later
"""Sidebar panels and the preset menu."""

from __future__ import annotations

import bpy

from . import presets_menu, sidebar

CLASSES = (*presets_menu.CLASSES, *sidebar.CLASSES)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)


def unregister():
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
