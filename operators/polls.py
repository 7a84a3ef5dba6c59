# SPDX-License-Identifier: GPL-3.0-or-later
"""What operators need before they can run, for their ``poll``: a greyed-out button says why
(``poll_message_set``), in the same words the operator would report."""

from __future__ import annotations

from ..blender import checks, surfaces


def scene(cls, context) -> bool:
    if context.scene is None:
        cls.poll_message_set("No scene")
        return False
    return True


def brush_and_paper(cls, context) -> bool:
    st = checks.settings(context.scene)
    try:
        checks.require_brush_and_paper(st)
    except checks.UserError as exc:
        cls.poll_message_set(str(exc))
        return False
    return True


def recording(cls, context) -> bool:
    if checks.settings(context.scene).recording is None:
        cls.poll_message_set("No recording yet: bake the brush's animation, paint, or import one")
        return False
    return True


def selected_meshes(context) -> list:
    """The selected meshes other than the paper plane (a mesh that is the paper itself, set
    up with setup(surface=True), counts: its writing can be carved into it)."""
    st = checks.settings(context.scene)
    plane = None if surfaces.is_surface(st) else st.paper_object
    return [o for o in context.selected_objects or [] if o.type == "MESH" and o != plane]


def paper_image_and_meshes(cls, context) -> bool:
    """A paper image to read, and meshes to put it on."""
    if checks.settings(context.scene).paper_image is None:
        cls.poll_message_set("No paper image yet: run Setup and Simulate first")
        return False
    if not selected_meshes(context):
        cls.poll_message_set("Select one or more meshes (other than the paper)")
        return False
    return True


def object_mode(cls, context) -> bool:
    if context.mode != "OBJECT":
        cls.poll_message_set("Switch to Object Mode first")
        return False
    return True
