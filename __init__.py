# SPDX-License-Identifier: GPL-3.0-or-later
"""Virtual Hairy Brush: a Blender extension (id ``hairy_brush``) around the engine in ``sim``.

Registration is explicit: the runtime state, properties, operators, handlers and panels register
in this order and unregister in reverse.
"""

from __future__ import annotations

from . import operators, panels
from .blender import handlers, properties, runtime

_MODULES = (runtime, properties, operators, handlers, panels)


def register():
    for mod in _MODULES:
        mod.register()


def unregister():
    for mod in reversed(_MODULES):
        mod.unregister()
