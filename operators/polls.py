# SPDX-License-Identifier: GPL-3.0-or-later
"""What operators need before they can run, for their ``poll``: a greyed-out button says why
(``poll_message_set``), in the same words the operator would report."""

from __future__ import annotations

from .. import bridge


def brush_and_paper(cls, context) -> bool:
    st = bridge.settings(context.scene)
    try:
        bridge.require_brush_and_paper(st)
    except bridge.UserError as exc:
        cls.poll_message_set(str(exc))
        return False
    return True


def recording(cls, context) -> bool:
    if bridge.settings(context.scene).recording is None:
        cls.poll_message_set("No recording yet: bake the brush's animation, paint, or import one")
        return False
    return True


def object_mode(cls, context) -> bool:
    if context.mode != "OBJECT":
        cls.poll_message_set("Switch to Object Mode first")
        return False
    return True
