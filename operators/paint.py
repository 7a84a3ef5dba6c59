# SPDX-License-Identifier: GPL-3.0-or-later
"""hairy_brush.paint: live painting on the paper plane in the 3D viewport (Fig. 6(b)), or on a
mesh that is the paper (issue 17.4: the mouse's ray meets the mesh, sim.surface.ray_hit, and the
point is placed on the chart of the latest sample's frame; each sample's frame then follows).

The event logic is ``sim.engine.live.LiveBrush`` (no bpy, tested with Blender's event sequences);
this operator only projects the mouse onto the paper, stamps each event with the clock
(``time.perf_counter()``: the live samples follow the wall clock, see sim.live), gives the engine
a share of each timer tick, refreshes the image from the tiles that changed, moves the brush and
stores the stroke."""

from __future__ import annotations

import time

import bpy
from bpy_extras import view3d_utils
from mathutils import Matrix

from ..blender import (
    checks,
    images,
    playback,
    presets,
    primitives,
    recordings,
    runtime,
    surfaces,
    transforms,
)
from ..sim import surface as surf
from ..sim.core import placement
from ..sim.core.params import HOVER_MM
from ..sim.engine.live import UNDO_KEY, LiveBrush, LiveEvent
from ..sim.engine.simulation import Simulation
from . import polls

TIMER_S = 1.0 / 120.0  # how often the modal operator gets the UI loop's attention
ENGINE_BUDGET_S = 0.030  # engine time per timer event while painting (the UI stays responsive)
REFRESH_HZ = 30.0  # image refreshes a second while painting, at most
REFRESH_SHARE = 0.15  # of the wall clock, at most, goes to refreshing (large papers refresh less)
NAVIGATION = {"MIDDLEMOUSE", "TRACKPADPAN", "TRACKPADZOOM", "NDOF_MOTION"}
NAVIGATION_PREFIX = "NUMPAD_"


def mouse_ray(context, mx: float, my: float):
    """(origin, direction) of the view ray under the mouse, in world space; None off a view."""
    region, rv3d = context.region, context.region_data
    if region is None or rv3d is None:
        return None
    origin = view3d_utils.region_2d_to_origin_3d(region, rv3d, (mx, my))
    return origin, view3d_utils.region_2d_to_vector_3d(region, rv3d, (mx, my))


def mouse_to_paper(context, st, mx: float, my: float, sim=None):
    """The paper point under the mouse in engine mm: on a surface, the chart position (near
    ``sim``'s latest frame) of the point where the ray meets the mesh; None when it misses."""
    return ray_to_paper(st, mouse_ray(context, mx, my), sim)


def ray_to_paper(st, ray, sim=None):
    """mouse_to_paper for a world ray (origin, direction), or None."""
    if ray is None:
        return None
    if surfaces.is_surface(st):
        hit = surfaces.surface_ray(st, *ray)
        if hit is None or sim is None or not sim.surface.frames:
            return None
        paper = sim.surface
        return surf.chart_xy_over(paper.surface, paper.frames[-1], hit.point, paper.near)
    return placement.ray_to_paper(transforms.engine_to_world(st, st.paper_object), *ray)


def start_on_surface(scene, ray) -> tuple[Simulation, tuple | None]:
    """The simulation at the end of the scene's recording on its surface (a fresh one, with its
    first frame where the mouse's world ray meets the mesh, when there is none), and the
    mouse's chart position."""
    st = checks.settings(scene)
    hit = surfaces.surface_ray(st, *ray) if ray is not None else None
    if st.recording is not None:
        pb = playback.playback_for(scene)
        sim = pb.seek(len(pb.rec.samples))
    elif hit is None:
        raise checks.UserError(
            f"Start painting with the mouse over '{st.paper_object.name}' (the paper surface)"
        )
    else:
        surface = surfaces.mesh_surface(st.paper_object)[0]
        frame = surf.new_frame(surface, hit, None, surfaces.surface_origin(st))
        hover = presets.hair_length(st) + HOVER_MM
        rec = recordings.new_recording(scene, [[frame[0], frame[1], hover, 0.0, 0.0, 0.0]])
        rec.extra[recordings.SURFACE_KEY] = {"frames": [frame.tolist()]}
        sim = Simulation(rec, surfaces.surface_paper(st, rec)).run()
    paper = sim.surface
    xy = (
        None
        if hit is None
        else surf.chart_xy_over(paper.surface, paper.frames[-1], hit.point, paper.near)
    )
    return sim, xy


def start_simulation(scene, xy) -> tuple[Simulation, bool]:
    """The simulation at the end of the scene's recording, or a fresh one (True) hovering at
    ``xy`` when there is none."""
    st = checks.settings(scene)
    if st.recording is not None:
        pb = playback.playback_for(scene)
        return pb.seek(len(pb.rec.samples)), False
    geom_len = presets.hair_length(st)
    x, y = xy if xy is not None else (st.paper_width_mm / 2, st.paper_height_mm / 2)
    rec = recordings.new_recording(scene, [[x, y, geom_len + HOVER_MM, 0.0, 0.0, 0.0]])
    return Simulation(rec).run(), True


def keep_stroke(scene, live: LiveBrush):
    """Store the recording with the new stroke (marked as painted, so a bake does not replace
    it unasked); the playback continues from the live state."""
    rec = live.sim.rec
    if live.sim.surface is not None:  # the frames the samples were simulated in
        frames = live.sim.surface.frames[: len(rec.samples)]
        rec.extra[recordings.SURFACE_KEY] = {"frames": [f.tolist() for f in frames]}
    info = rec.extra.setdefault("blender", {})
    info[recordings.PAINTED_KEY] = int(info.get(recordings.PAINTED_KEY, 0)) + len(live.new_samples)
    recordings.store_recording(checks.settings(scene), rec)
    playback.adopt(scene, live.sim)


class HAIRY_BRUSH_OT_paint(bpy.types.Operator):
    """Paint with the brush: move the mouse over the paper, hold the left button to press,
    wheel = press depth, Q/W E/R C/V = tilt and twist (Shift x4, left button x2), D = dip;
    release or Enter keeps the stroke, Ctrl+Z takes back this stroke (or, before pressing, the
    last one kept), Esc or right-click cancels"""

    bl_idname = "hairy_brush.paint"
    bl_label = "Paint"
    bl_options = {"REGISTER", "UNDO", "BLOCKING"}

    @classmethod
    def poll(cls, context):
        if context.area is None or context.area.type != "VIEW_3D":
            cls.poll_message_set("Paint from a 3D Viewport")
            return False
        if checks.settings(context.scene).paper_object is None:
            cls.poll_message_set("No paper plane: run Setup first")
            return False
        return polls.object_mode(cls, context)

    def invoke(self, context, event):
        scene = context.scene
        st = checks.settings(scene)
        if st.paper_object is None:
            self.report({"ERROR"}, "No paper plane: run Setup first")
            return {"CANCELLED"}
        mx, my = event.mouse_region_x, event.mouse_region_y
        try:
            img = images.ensure_paper_image(st)
            if surfaces.is_surface(st):
                sim, xy = start_on_surface(scene, mouse_ray(context, mx, my))
            else:
                xy = mouse_to_paper(context, st, mx, my)
                sim, _fresh = start_simulation(scene, xy)
        except checks.USER_ERRORS as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        self.start(context, img, LiveBrush(sim, st.paint_press_mm, st.paint_angle_step, xy))
        wm = context.window_manager
        self._timer = wm.event_timer_add(TIMER_S, window=context.window)
        wm.modal_handler_add(self)
        context.workspace.status_text_set(
            "Hold LMB: press | Wheel: depth | Q/W E/R C/V: d q r | D: dip | "
            "Enter/release: keep | Ctrl+Z: undo stroke | Esc/RMB: cancel"
        )
        return {"RUNNING_MODAL"}

    def start(self, context, img, live: LiveBrush):
        """The stroke's state (also used by tests, which have no window to run a modal in)."""
        st = checks.settings(context.scene)
        self._img = img
        self._live = runtime.get().painter = live  # the painting in progress, while it lasts
        self._brush_mw = st.brush_object.matrix_world.copy() if st.brush_object else None
        self._last_draw = 0.0
        self._refresh_s = 0.0  # what the last refresh cost
        self._timer = None
        images.show_paper(img, live.sim.paper, live.sim.index)  # later refreshes: what changed
        live.handle(LiveEvent("START", "NOTHING", time=time.perf_counter()))

    def modal(self, context, event):
        st = checks.settings(context.scene)
        if event.type in NAVIGATION or event.type.startswith(NAVIGATION_PREFIX):
            return {"PASS_THROUGH"}
        now = time.perf_counter()  # the sample clock: when the event is handled
        if event.type == "D" and event.value == "PRESS":
            self._live.dip(st.dip_depth, st.ink_color, st.dip_wetness, now, follows_ink=True)
            return {"RUNNING_MODAL"}
        xy = None
        if event.type in ("MOUSEMOVE", "INBETWEEN_MOUSEMOVE", "LEFTMOUSE"):
            mx, my = event.mouse_region_x, event.mouse_region_y
            xy = mouse_to_paper(context, st, mx, my, self._live.sim)
        ev = LiveEvent(
            event.type,
            event.value,
            xy,
            float(getattr(event, "pressure", 1.0)),
            tuple(getattr(event, "tilt", (0.0, 0.0))),
            bool(getattr(event, "is_tablet", False)),
            bool(event.shift),
            now,
            bool(event.ctrl or event.oskey),
        )
        return self.step(context, ev)

    def step(self, context, ev: LiveEvent) -> set:
        """One event: the clock makes the samples due, the engine simulates for a share of the
        UI loop's time, and the image is refreshed at most REFRESH_HZ times a second and with
        at most REFRESH_SHARE of the time, so the engine keeps up on a large paper."""
        state = self._live.handle(ev)
        if state == "RUNNING":
            if ev.type == "TIMER":
                self._live.advance(ENGINE_BUDGET_S)
                self.show(context, final=False)
            elif ev.type == UNDO_KEY:  # the stroke was taken back: show the paper without it
                self._last_draw = 0.0
                self.show(context, final=False)
            return {"RUNNING_MODAL"}
        self._finish(context)
        if state == "UNDO":  # nothing painted yet: Blender's undo takes back the last stroke
            self.show(context, final=True)
            return {"CANCELLED", "PASS_THROUGH"}
        if state == "CANCELLED":
            self.show(context, final=True)
            return {"CANCELLED"}
        keep_stroke(context.scene, self._live)
        self.show(context, final=True)
        self.report({"INFO"}, f"Stroke of {len(self._live.new_samples)} samples kept")
        return {"FINISHED"}

    def show(self, context, final: bool):
        """The paper as simulated so far; the brush empty (and the primitive surfaces, when
        built) at the live pose."""
        now = time.perf_counter()
        wait = max(1.0 / REFRESH_HZ, self._refresh_s / REFRESH_SHARE)
        if not final and now - self._last_draw < wait:
            return
        scene = context.scene
        st = checks.settings(scene)
        sim = self._live.sim
        images.show_paper(self._img, sim.paper, sim.index)
        self._last_draw = time.perf_counter()
        self._refresh_s = self._last_draw - now
        if final:
            return
        if st.brush_object is not None:
            pose = sim.rec.samples[-1]
            if sim.surface is not None:  # in the latest frame the engine has made
                mw = surfaces.surface_matrix(st, sim.surface.frames[-1], pose)
            else:
                mw = transforms.matrix_from_sample(st, st.paper_object.matrix_world, pose)
            st.brush_object.matrix_world = Matrix(mw.tolist())
        if primitives.primitive_objects(scene):
            primitives.sync_primitives(scene, sim, create=False)

    def _finish(self, context):
        runtime.get().painter = None
        if self._timer is not None:
            context.window_manager.event_timer_remove(self._timer)
            context.workspace.status_text_set(None)
        st = checks.settings(context.scene)
        if st.brush_object is not None and self._brush_mw is not None:
            st.brush_object.matrix_world = self._brush_mw

    def cancel(self, context):
        self._live.cancel()
        self._finish(context)
        self.show(context, final=True)
