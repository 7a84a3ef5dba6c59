# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.open_example: the example that comes inside the extension (examples/strokes.json,
the character 永 written by the brush), imported, set up and simulated: calligraphy on the
paper straight after installing (issue 29.10)."""

from __future__ import annotations

from pathlib import Path

import bpy

from ..blender import checks
from . import polls

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "strokes.json"


class HAIRY_BRUSH_OT_open_example(bpy.types.Operator):
    """Import the example recording that comes with the extension (the character 永), set up the
    brush and paper for it and simulate it"""

    bl_idname = "hairy_brush.open_example"
    bl_label = "Load the Example (永)"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return polls.object_mode(cls, context)

    def execute(self, context):
        if not EXAMPLE.is_file():
            self.report({"ERROR"}, f"The example is missing from the extension ({EXAMPLE})")
            return {"CANCELLED"}
        try:
            for op, kw in (
                (bpy.ops.hairy_brush.import_recording, {"filepath": str(EXAMPLE)}),
                (bpy.ops.hairy_brush.setup, {}),
                (bpy.ops.hairy_brush.simulate, {}),
            ):
                if op("EXEC_DEFAULT", **kw) != {"FINISHED"}:
                    return {"CANCELLED"}
        except RuntimeError as exc:  # an operator's own error report
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        st = checks.settings(context.scene)
        self.report({"INFO"}, f"The example: 永 on {st.paper_width_mm:g} mm paper")
        return {"FINISHED"}
