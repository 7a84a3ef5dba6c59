# SPDX-License-Identifier: GPL-3.0-or-later
"""Operators (``bpy.ops.hairy_brush.*``), one a file; thin glue over the engine in ``sim``."""

from __future__ import annotations

import bpy

from .add_settings_preset import HAIRY_BRUSH_OT_add_settings_preset
from .apply_preset import HAIRY_BRUSH_OT_apply_preset
from .apply_to_mesh import HAIRY_BRUSH_OT_apply_to_mesh
from .bake_cache import HAIRY_BRUSH_OT_bake_cache
from .bake_samples import HAIRY_BRUSH_OT_bake_samples
from .bake_sequence import HAIRY_BRUSH_OT_bake_sequence
from .build_primitives import HAIRY_BRUSH_OT_build_primitives
from .dip import HAIRY_BRUSH_OT_dip
from .export_grease_pencil import HAIRY_BRUSH_OT_export_grease_pencil
from .export_image import HAIRY_BRUSH_OT_export_image
from .export_recording import HAIRY_BRUSH_OT_export_recording
from .export_svg import HAIRY_BRUSH_OT_export_svg
from .fit_parameters import HAIRY_BRUSH_OT_fit_parameters
from .follow_ink import HAIRY_BRUSH_OT_follow_ink
from .imitate_image import HAIRY_BRUSH_OT_imitate_image
from .import_recording import HAIRY_BRUSH_OT_import_recording
from .ink_matte import HAIRY_BRUSH_OT_ink_matte
from .open_example import HAIRY_BRUSH_OT_open_example
from .paint import HAIRY_BRUSH_OT_paint
from .relief import HAIRY_BRUSH_OT_relief
from .rewrite_cell import HAIRY_BRUSH_OT_rewrite_cell
from .setup import HAIRY_BRUSH_OT_setup
from .sign_work import HAIRY_BRUSH_OT_sign_work
from .simulate import HAIRY_BRUSH_OT_simulate
from .write_character import HAIRY_BRUSH_OT_write_character
from .write_text import HAIRY_BRUSH_OT_write_text

CLASSES = (
    HAIRY_BRUSH_OT_setup,
    HAIRY_BRUSH_OT_bake_samples,
    HAIRY_BRUSH_OT_simulate,
    HAIRY_BRUSH_OT_paint,
    HAIRY_BRUSH_OT_dip,
    HAIRY_BRUSH_OT_follow_ink,
    HAIRY_BRUSH_OT_build_primitives,
    HAIRY_BRUSH_OT_bake_sequence,
    HAIRY_BRUSH_OT_bake_cache,
    HAIRY_BRUSH_OT_import_recording,
    HAIRY_BRUSH_OT_export_recording,
    HAIRY_BRUSH_OT_apply_to_mesh,
    HAIRY_BRUSH_OT_relief,
    HAIRY_BRUSH_OT_write_character,
    HAIRY_BRUSH_OT_write_text,
    HAIRY_BRUSH_OT_sign_work,
    HAIRY_BRUSH_OT_rewrite_cell,
    HAIRY_BRUSH_OT_imitate_image,
    HAIRY_BRUSH_OT_fit_parameters,
    HAIRY_BRUSH_OT_apply_preset,
    HAIRY_BRUSH_OT_add_settings_preset,
    HAIRY_BRUSH_OT_ink_matte,
    HAIRY_BRUSH_OT_export_image,
    HAIRY_BRUSH_OT_export_svg,
    HAIRY_BRUSH_OT_export_grease_pencil,
    HAIRY_BRUSH_OT_open_example,
)

register, unregister = bpy.utils.register_classes_factory(CLASSES)
