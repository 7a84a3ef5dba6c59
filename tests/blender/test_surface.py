# SPDX-License-Identifier: GPL-3.0-or-later
"""Writing on a mesh's surface in Blender (issue 17): setup(surface=True), baking and simulating
on the surface, live painting on it, relief, undo/save/reload and the messages (real bpy)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.blender.helpers import ext

bpy = pytest.importorskip("bpy")

from sim.core.params import load_preset  # noqa: E402
from sim.core.recording import DEFAULT_BRUSH  # noqa: E402
from sim.paper.display import linear_to_srgb  # noqa: E402

HAIR = load_preset("brush", DEFAULT_BRUSH).data["geometry"]["hair_length_mm"]  # the default's
R_MM = 40.0  # the cylinder's radius


def ink(img) -> np.ndarray:
    """(H, W) darkness of the image's visible colour, bottom row first (0 = the paper's)."""
    a = np.empty(len(img.pixels), np.float32)
    img.pixels.foreach_get(a)
    rgb = linear_to_srgb(a.reshape(img.size[1], img.size[0], 4)[..., :3]).mean(axis=2)
    return rgb.max() - rgb


def select_only(*objs):
    for ob in bpy.context.scene.objects:
        ob.select_set(ob in objs)
    if objs:
        bpy.context.view_layer.objects.active = objs[0]


def cylinder(vertices=48):
    bpy.ops.mesh.primitive_cylinder_add(vertices=vertices, radius=R_MM / 1000, depth=0.12)
    return bpy.context.active_object


def surface_scene(obj, ppm=3.0):
    st = bpy.context.scene.hairy_brush
    st.px_per_mm = ppm
    select_only(obj)
    assert bpy.ops.hairy_brush.setup(surface=True) == {"FINISHED"}
    return st


def key_pose(brush, frame, loc, rot=(0.0, 0.0, 0.0)):
    brush.location, brush.rotation_euler = loc, rot
    brush.keyframe_insert("location", frame=frame)
    brush.keyframe_insert("rotation_euler", frame=frame)


def key_around(st, angles_deg, press, z=0.0, first=1, step=2):
    """Keyframe the brush upright against the cylinder's side (its hair along the normal) at
    each angle (0 = the -y side, the front), pressing ``press`` mm; returns the last frame."""
    b = st.brush_object
    b.rotation_mode = "XYZ"  # Rz(a) Rx(90 deg): turned about the cylinder's axis
    f = first
    for a, p in zip(np.radians(angles_deg), press, strict=True):
        dist = (R_MM + HAIR - p) / 1000
        key_pose(b, f, (dist * math.sin(a), -dist * math.cos(a), z), (math.pi / 2, 0.0, a))
        f += step
    sc = bpy.context.scene
    sc.frame_start, sc.frame_end = first, f - step
    for fc in ext().blender.keyframes.fcurves(b.animation_data):
        for kp in fc.keyframe_points:
            kp.interpolation = "LINEAR"
    return f - step


def presses(n, press=3.0, lead=3):
    p = np.full(n, -5.0)
    p[lead:-lead] = press
    return p


def texels(sc):
    return ext().blender.playback.playback_for(sc).sim.surface.texels


# ----------------------------------------------------------------------------- set-up
def test_setup_makes_the_selected_mesh_the_paper(hb):
    cyl = cylinder()
    st = surface_scene(cyl, ppm=3.0)
    assert st.paper_object == cyl and ext().blender.surfaces.is_surface(st)
    surface = ext().blender.surfaces.mesh_surface(cyl)[0]
    side = math.sqrt(surface.area_mm2 / surface.uv_area)
    n = round(side * 3.0)
    assert tuple(st.paper_image.size) == (n, n) and abs(st.paper_width_mm - side) < 1e-3
    # the mesh's material shows the paper image through its active UV map
    mat = cyl.data.materials[0]
    tex = mat.node_tree.nodes[ext().blender.materials.INK_NODE]
    assert tex.image == st.paper_image
    uv = next(n for n in mat.node_tree.nodes if n.type == "UVMAP")
    assert uv.uv_map == cyl.data.uv_layers.active.name
    # the brush hovers above the surface, its hair along the normal (the front, -y, of a vase)
    mw = np.array(st.brush_object.matrix_world)
    np.testing.assert_allclose(mw[:3, 2], [0.0, -1.0, 0.0], atol=0.05)
    dist = math.hypot(mw[0, 3], mw[1, 3]) * 1000 - R_MM
    assert abs(dist - (HAIR + 5.0)) < 0.5
    assert cyl.dimensions.x == pytest.approx(0.08, abs=1e-6)  # the mesh keeps its shape
    shown = _paper_panel()
    assert ("op", "hairy_brush.setup", "Write on Selected Mesh") in shown
    assert ("label", "Writing on the surface of 'Cylinder'") in shown
    st.paper_width_mm = 300.0  # the size of a surface's texture is not a plane's to resize
    assert len(cyl.data.vertices) == 96
    # and Set Up again without surface=True: a flat paper plane again, the mesh untouched
    assert bpy.ops.hairy_brush.setup() == {"FINISHED"}
    assert st.paper_object != cyl and not ext().blender.surfaces.is_surface(st)
    assert len(st.paper_object.data.vertices) == 4 and len(cyl.data.materials) == 1
    assert st.brush_object.parent == st.paper_object
    assert st.brush_object.matrix_world.translation.z == pytest.approx((HAIR + 5) / 1000)


def _paper_panel() -> list:
    """What the sidebar's Paper panel draws: ("op", idname, text) and ("label", text)."""
    from types import SimpleNamespace

    log = []

    class Layout:
        enabled, use_property_split = True, False

        def operator(self, idname, text="", **_kw):
            log.append(("op", idname, text))
            return SimpleNamespace()

        def label(self, text="", **_kw):
            log.append(("label", text))

        def prop(self, *_a, **_kw):
            pass

        menu = prop_search = separator = prop

        def row(self, **_kw):
            return self

        column = box = row

    panel = ext().panels.sidebar.HAIRY_BRUSH_PT_paper
    panel.draw(SimpleNamespace(layout=Layout()), bpy.context)
    return log


def test_meshes_that_cannot_be_paper_and_a_brush_that_never_touches_get_clear_messages(hb, capfd):
    st = bpy.context.scene.hairy_brush
    select_only()
    with pytest.raises(RuntimeError, match="Select a mesh to write on"):
        bpy.ops.hairy_brush.setup(surface=True)
    me = bpy.data.meshes.new("NoUV")
    me.from_pydata([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [], [(0, 1, 2)])
    no_uv = bpy.data.objects.new("NoUV", me)
    bpy.context.scene.collection.objects.link(no_uv)
    select_only(no_uv)
    with pytest.raises(RuntimeError, match="Mesh 'NoUV' has no UV map: add one"):
        bpy.ops.hairy_brush.setup(surface=True)
    me = bpy.data.meshes.new("Fin")
    v = [(0, 0, 0), (0.1, 0, 0), (0, 0.1, 0), (0, -0.1, 0), (0, 0, 0.1)]
    me.from_pydata(v, [], [(0, 1, 2), (0, 1, 3), (0, 1, 4)])  # three faces on one edge
    me.uv_layers.new(name="UVMap")
    for k, loop in enumerate(me.loops):
        me.uv_layers.active.data[loop.index].uv = (0.1 * (k % 3), 0.3 * (k // 3) + 0.1 * (k % 2))
    fin = bpy.data.objects.new("Fin", me)
    bpy.context.scene.collection.objects.link(fin)
    select_only(fin)
    with pytest.raises(RuntimeError, match="Mesh 'Fin' is not manifold: 1 edge"):
        bpy.ops.hairy_brush.setup(surface=True)
    tiled = cylinder()
    tiled.name = "Tiled"
    for d in tiled.data.uv_layers.active.data:
        d.uv = (d.uv[0] + 1.0, d.uv[1])  # the UDIM tile 1002
    select_only(tiled)
    with pytest.raises(RuntimeError, match=r"Mesh 'Tiled''s UV map reaches outside the image"):
        bpy.ops.hairy_brush.setup(surface=True)
    assert st.paper_object is None  # nothing was set up
    bpy.data.objects.remove(tiled)
    cyl = cylinder()
    st = surface_scene(cyl)
    key_around(st, np.linspace(-20, 20, 11), np.full(11, -4.0))  # 4 mm short of the surface
    capfd.readouterr()
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    out = capfd.readouterr().out
    lowest = f"its lowest point is z = {HAIR + 4:.1f} mm"
    assert f"never touches the surface of 'Cylinder': {lowest}" in out


# ----------------------------------------------------------------------------- the ink
@pytest.mark.slow
def test_a_flat_grid_with_turned_scaled_uvs_writes_the_planes_ink_through_them(hb):
    # no fibre on either sheet: the fibre field is fixed per pixel of the sheet (a hash of its
    # row and column, like the grain), and the texture's texels are not the plane's pixels
    # (turned, halved), so it would refuse thin ink at other places of the two marks' fringes
    sc = bpy.context.scene
    st = sc.hairy_brush
    st.px_per_mm, st.paper_fibre = 2.0, 0.0
    st.paper_texture = 0.0  # the ink compared, not the sheet (a mesh made paper shows none)
    assert bpy.ops.hairy_brush.setup() == {"FINISHED"}  # the flat plane, 200 x 200 mm

    def stroke(brush):
        sc.frame_start, sc.frame_end = 1, 48
        for f, x, z in ((1, -0.05, HAIR + 5), (8, -0.05, HAIR - 4), (40, 0.05, HAIR - 4)):
            brush.location = (x, 0.01, z / 1000)
            brush.keyframe_insert("location", frame=f)
        brush.location = (0.06, 0.01, (HAIR + 5) / 1000)
        brush.keyframe_insert("location", frame=48)

    stroke(st.brush_object)
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}
    plane = ink(st.paper_image)
    bpy.ops.wm.read_homefile(use_empty=True)
    sc = bpy.context.scene
    st = sc.hairy_brush
    st.px_per_mm, st.paper_fibre = 2.0, 0.0
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=8, y_subdivisions=8, size=0.2)
    grid = bpy.context.active_object
    a = math.radians(30.0)
    for loop in grid.data.uv_layers.active.data:  # turned 30 degrees, half the size
        u, v = loop.uv[0] - 0.5, loop.uv[1] - 0.5
        loop.uv = (0.5 + 0.5 * (u * math.cos(a) - v * math.sin(a)),
                   0.5 + 0.5 * (u * math.sin(a) + v * math.cos(a)))  # fmt: skip
    surface_scene(grid, ppm=2.0)
    stroke(st.brush_object)
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}
    assert ext().blender.recordings.recording_from_scene(sc).resolve()[2].fibre == 0.0
    assert tuple(st.paper_image.size) == (800, 800)  # 400 mm of texture: the UVs are halved
    tp = texels(sc)
    inside = np.abs(tp.xyz[:, :2]).max(axis=1) < 100.0
    px = np.floor((tp.xyz[inside, :2] + 100.0) * 2.0).astype(int)
    on_plane = plane[px[:, 1], px[:, 0]]
    on_grid = ink(st.paper_image).ravel()[tp.index[inside]]
    a, b = on_plane > 0.3, on_grid > 0.3
    assert a.sum() > 300
    assert (a & b).sum() / (a | b).sum() > 0.93
    assert np.abs(on_plane - on_grid).mean() < 0.02


@pytest.mark.slow
def test_a_straight_stroke_along_a_cylinder_inks_only_under_its_path_with_constant_width(hb):
    sc = bpy.context.scene
    st = surface_scene(cylinder(vertices=64))
    b = st.brush_object
    dist = (R_MM + HAIR - 3.0) / 1000
    sc.frame_start, sc.frame_end = 1, 40
    key_pose(b, 1, (0.0, -dist - 0.008, -0.04), (math.pi / 2, 0, 0))
    key_pose(b, 6, (0.0, -dist, -0.04), (math.pi / 2, 0, 0))
    key_pose(b, 35, (0.0, -dist, 0.04), (math.pi / 2, 0, 0))
    key_pose(b, 40, (0.0, -dist - 0.008, 0.04), (math.pi / 2, 0, 0))
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}
    tp = texels(sc)
    inked = ink(st.paper_image).ravel()[tp.index] > 0.3
    X = tp.xyz[inked]
    assert inked.sum() > 300
    assert (X[:, 1] < -R_MM + 2.0).all()  # on the front, under the path
    assert np.abs(X[:, 0]).max() < 6.0 and X[:, 2].min() > -47.0 and X[:, 2].max() < 47.0
    widths = [np.ptp(X[(X[:, 2] >= z) & (X[:, 2] < z + 5.0), 0]) for z in range(-25, 25, 5)]
    assert min(widths) > 2.0 and max(widths) - min(widths) < 0.6


@pytest.mark.slow
def test_a_stroke_across_the_uv_seam_has_no_gap(hb):
    sc = bpy.context.scene
    cyl = cylinder()
    st = surface_scene(cyl)
    tp = ext().blender.surfaces.surface_paper(st, _one_frame_recording(st)).texels
    side = np.abs(tp.normal[:, 2]) < 0.5
    u = (tp.index % tp.W)[side]
    ang = np.degrees(np.arctan2(tp.xyz[side, 0], -tp.xyz[side, 1]))  # 0 at the front
    seam = float(ang[np.argmin(u)])  # where the side's strip starts in the texture
    n = 31
    key_around(st, seam + np.linspace(-30, 30, n), presses(n))
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}
    tp = texels(sc)
    dark = ink(st.paper_image).ravel()[tp.index]
    inked = (dark > 0.3) & (np.abs(tp.normal[:, 2]) < 0.5)
    a = np.degrees(np.arctan2(tp.xyz[inked, 0], -tp.xyz[inked, 1])) - seam
    a = (a + 180.0) % 360.0 - 180.0
    cols = (tp.index % tp.W)[inked]
    assert cols.min() < 0.1 * tp.W and cols.max() > 0.5 * tp.W  # both ends of the strip
    assert np.histogram(a, bins=np.arange(-20.0, 20.5, 1.0))[0].min() > 0  # no gap


def _one_frame_recording(st):
    b = ext().blender.recordings
    rec = b.new_recording(bpy.context.scene, [[0.0, 0.0, 50.0, 0.0, 0.0, 0.0]])
    rec.extra[b.SURFACE_KEY] = {"frames": [[0.0, 0.0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0]]}
    return rec


# ----------------------------------------------------------------------------- relief, files
def _carved_cylinder(follow: str):
    """A cylinder that is the paper, written round and carved 1.5 mm into itself; returns the
    cylinder, the settings, the relief modifier and its vertices' radii with the relief on and
    off (the same vertices) and their UVs."""
    cyl = cylinder()
    st = surface_scene(cyl)
    n = 21
    key_around(st, np.linspace(-30, 30, n), presses(n, 6.0, 2))
    bpy.ops.hairy_brush.bake_samples()
    bpy.ops.hairy_brush.simulate()
    select_only(cyl)  # the paper itself can be carved
    res = bpy.ops.hairy_brush.relief(mode="CARVE", depth_mm=1.5, detail=4, follow=follow)
    assert res == {"FINISHED"}
    relief = cyl.modifiers[ext().operators.relief.RELIEF]
    r, uv = _radii_and_uvs(cyl)
    relief.show_viewport = False
    r0, _uv = _radii_and_uvs(cyl)  # the same vertices, not displaced
    relief.show_viewport = True
    return cyl, st, relief, r, r0, uv


@pytest.mark.slow
def test_relief_carves_the_surface_under_the_ink_by_the_depth(hb):
    # the image value (the density relief, the default, is tested below)
    cyl, st, relief, r, r0, uv = _carved_cylinder("VALUE")
    img = st.paper_image
    raw = np.empty(len(img.pixels), np.float32)
    img.pixels.foreach_get(raw)
    lum = raw.reshape(img.size[1], img.size[0], 4)[..., :3].mean(axis=2)
    depth = 1.0 - lum / np.median(lum)  # 0 on bare paper, 1 under full ink
    w = img.size[0]
    px = np.clip((uv * w).astype(int), 1, w - 2)
    win = np.stack([depth[px[:, 1] + dy, px[:, 0] + dx] for dy in (-1, 0, 1) for dx in (-1, 0, 1)])
    moved = r0 - r
    bare = win.max(axis=0) < 1e-4
    inked = (win.min(axis=0) > 0.5) & (np.ptp(win, axis=0) < 0.02)
    assert bare.sum() > 1000 and inked.sum() > 10
    np.testing.assert_allclose(moved[bare], 0.0, atol=1e-6)  # nowhere else
    np.testing.assert_allclose(moved[inked], 1.5 * win.mean(axis=0)[inked], atol=0.02)
    assert moved.max() < 1.5 + 0.01 and moved.min() > -1e-6  # never beyond the depth


def _radii_and_uvs(obj):
    """The evaluated mesh's vertices' distances to the z axis (mm) and their UVs."""
    dg = bpy.context.evaluated_depsgraph_get()
    me = obj.evaluated_get(dg).to_mesh()
    co = np.empty(len(me.vertices) * 3)
    me.vertices.foreach_get("co", co)
    uv = np.zeros((len(me.vertices), 2))
    for loop in me.loops:
        uv[loop.vertex_index] = me.uv_layers.active.data[loop.index].uv
    obj.evaluated_get(dg).to_mesh_clear()
    co = co.reshape(-1, 3)
    return np.hypot(co[:, 0], co[:, 1]) * 1000, uv


@pytest.mark.slow
def test_undo_save_and_reload_keep_the_surface_and_its_writing(hb, tmp_path):
    sc = bpy.context.scene
    cyl = cylinder()
    st = surface_scene(cyl)
    n = 15
    key_around(st, np.linspace(-20, 20, n), presses(n))
    bpy.ops.hairy_brush.bake_samples()
    _undo_push("baked")
    before = ink(st.paper_image)
    bpy.ops.hairy_brush.simulate()
    _undo_push("simulated")
    after = ink(bpy.context.scene.hairy_brush.paper_image)
    assert (after > 0.3).sum() > 100
    _call("undo")
    np.testing.assert_array_equal(ink(bpy.context.scene.hairy_brush.paper_image), before)
    _call("redo")
    st = bpy.context.scene.hairy_brush
    np.testing.assert_array_equal(ink(st.paper_image), after)
    text = st.recording.as_string()
    assert '"surface":{"frames":[\n' in text  # a frame a line, as the samples
    path = tmp_path / "vase.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    bpy.ops.wm.read_homefile(use_empty=True)
    bpy.ops.wm.open_mainfile(filepath=str(path))
    st = bpy.context.scene.hairy_brush
    assert st.paper_object.name == "Cylinder" and ext().blender.surfaces.is_surface(st)
    assert st.recording.as_string() == text
    np.testing.assert_array_equal(ink(st.paper_image), after)
    st.paper_image.pixels.foreach_set(np.ones(len(st.paper_image.pixels), np.float32))
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}  # replayed after loading: the same
    np.testing.assert_allclose(ink(st.paper_image), after, atol=1e-6)
    sc = bpy.context.scene
    assert sc.hairy_brush.paper_object.data.materials[0] is not None


def _undo_push(message):
    with bpy.context.temp_override(window=bpy.context.window_manager.windows[0]):
        bpy.ops.ed.undo_push(message=message)


def _call(name):
    with bpy.context.temp_override(window=bpy.context.window_manager.windows[0]):
        getattr(bpy.ops.ed, name)()


def test_live_painting_on_the_surface_follows_the_mesh_and_replays(hb):
    LiveEvent = ext().sim.engine.live.LiveEvent  # noqa: N806 - the installed copy's class
    sc = bpy.context.scene
    st = surface_scene(cylinder())
    paint = ext().operators.paint

    def ray(deg, z=0.0):  # a view ray from in front, aimed at the cylinder's axis
        a = math.radians(deg)
        return (np.array([math.sin(a), -math.cos(a), z]), np.array([-math.sin(a), math.cos(a), 0]))

    sim, xy = paint.start_on_surface(sc, ray(-20.0))
    live = ext().sim.engine.live.LiveBrush(sim, press_mm=4.0, step_deg=2.0, xy=xy)
    live.handle(LiveEvent("LEFTMOUSE", "PRESS", xy))
    for i in range(50):
        xy = paint.ray_to_paper(st, ray(-20.0 + i), live.sim)
        live.handle(LiveEvent("MOUSEMOVE", "NOTHING", xy))
        live.handle(LiveEvent("TIMER", "NOTHING"))
        live.advance()
    assert live.handle(LiveEvent("LEFTMOUSE", "RELEASE", xy)) == "FINISHED"
    paint.keep_stroke(sc, live)
    frames = np.array(live.sim.surface.frames)
    ang = np.degrees(np.arctan2(frames[:, 2], -frames[:, 3]))
    assert ang[-1] > 25.0  # the frames went round the cylinder with the mouse
    assert np.abs(np.hypot(frames[:, 2], frames[:, 3]) - R_MM).max() < 0.5
    rec = ext().blender.recordings.recording_from_scene(sc)
    replay = (
        ext()
        .sim.engine.simulation.Simulation(rec, ext().blender.surfaces.surface_paper(st, rec))
        .run()
    )
    np.testing.assert_array_equal(replay.paper.ink, live.sim.paper.ink)
    assert (replay.paper.ink.mean(axis=2) > 0.3).sum() > 100


@pytest.mark.slow
def test_a_stroke_along_a_uv_spheres_seam_and_over_its_pole_has_no_gap(hb):
    from mathutils import Matrix

    sc = bpy.context.scene
    bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16, radius=0.05)
    st = surface_scene(bpy.context.active_object)
    me = st.paper_object.data
    uv = me.uv_layers.active.data
    on_seam = [me.vertices[lp.vertex_index].co for lp in me.loops if uv[lp.index].uv[0] < 1e-4]
    lon = math.atan2(on_seam[len(on_seam) // 2].y, on_seam[len(on_seam) // 2].x)
    b = st.brush_object
    b.rotation_mode = "QUATERNION"
    x = np.array([-math.sin(lon), math.cos(lon), 0.0])  # rays along the seam's edges
    lats = np.radians(np.linspace(20.0, 160.0, 36))
    press = presses(len(lats), 3.0, 2)
    for f, (lat, p) in enumerate(zip(lats, press, strict=True), start=1):
        n = np.array([math.cos(lat) * math.cos(lon), math.cos(lat) * math.sin(lon), math.sin(lat)])
        m = np.eye(4)
        m[:3, :3] = np.stack([x, np.cross(n, x), n], axis=1)
        m[:3, 3] = n * (50.0 + HAIR - p) / 1000
        b.matrix_world = Matrix(m.tolist())
        b.keyframe_insert("location", frame=f)
        b.keyframe_insert("rotation_quaternion", frame=f)
    sc.frame_start, sc.frame_end = 1, len(lats)
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    rec = ext().blender.recordings.recording_from_scene(sc)
    assert np.abs(rec.samples[:, 3:5]).max() < 5.0  # upright on the surface all the way
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}
    tp = texels(sc)
    inked = ink(st.paper_image).ravel()[tp.index] > 0.3
    X = tp.xyz[inked]
    along = np.degrees(np.arctan2(X[:, 2], X[:, 0] * math.cos(lon) + X[:, 1] * math.sin(lon)))
    assert np.histogram(along, bins=np.arange(45.0, 135.0, 2.0))[0].min() > 0  # over the pole
    u = (tp.index % tp.W)[inked] / tp.W
    assert (u < 0.05).any() and (u > 0.95).any()  # on both sides of the seam


@pytest.mark.slow
def test_a_density_relief_moves_the_surface_in_proportion_to_the_ink_and_follows_frames(hb):
    sc = bpy.context.scene
    cyl, st, relief, r, r0, uv = _carved_cylinder("DENSITY")
    density = ext().blender.playback.playback_for(sc).sim.paper.ink.mean(axis=2)
    w = density.shape[1]
    px = np.clip((uv * w).astype(int), 1, w - 2)
    win = np.stack(
        [density[px[:, 1] + dy, px[:, 0] + dx] for dy in (-1, 0, 1) for dx in (-1, 0, 1)]
    )
    even = np.ptp(win, axis=0) < 0.02
    moved = r0 - r
    part = even & (win.min(axis=0) > 0.05)
    assert part.sum() > 10 and (even & (win.max(axis=0) < 1e-6)).sum() > 1000
    np.testing.assert_allclose(moved[part], 1.5 * win.mean(axis=0)[part], atol=0.03)
    np.testing.assert_allclose(moved[even & (win.max(axis=0) < 1e-6)], 0.0, atol=1e-6)
    # live: the relief follows the paper to an earlier frame (less written, less carved)
    sc.frame_set(sc.frame_start + 10)  # a quarter of the way
    early = r0 - _radii_and_uvs(cyl)[0]
    assert 0.05 * moved.sum() < early.sum() < 0.5 * moved.sum()


# ----------------------------------------------------------------------------- Write Character
@pytest.mark.slow
def test_write_character_on_a_cylinder_lands_under_the_brush_at_its_size_and_replays(hb):
    """Write Character on a surface paper: the writing is laid on the cylinder around the point
    under the brush empty, at the size asked for (the texture keeps its size), the brush is
    keyframed over the surface, and a re-simulation of the stored recording shows the same
    image bit for bit."""
    from tests.paths import ROOT

    sc = bpy.context.scene
    cyl = cylinder()
    st = surface_scene(cyl, ppm=2.0)
    side, size_px = st.paper_width_mm, tuple(st.paper_image.size)
    b = st.brush_object
    a, z0 = math.radians(35.0), 12.0  # the brush 35 degrees round the side, 12 mm up
    b.rotation_mode = "XYZ"
    dist = (R_MM + HAIR + 5.0) / 1000
    b.location = (dist * math.sin(a), -dist * math.cos(a), z0 / 1000)
    b.rotation_euler = (math.pi / 2, 0.0, a)
    path = ROOT / "data" / "hanzi" / "十.json"
    size = 40.0
    assert bpy.ops.hairy_brush.write_character(filepath=str(path), size_mm=size, passes=1) == {
        "FINISHED"
    }
    assert st.paper_width_mm == side and tuple(st.paper_image.size) == size_px  # not resized
    rec = ext().blender.recordings.recording_from_scene(sc)
    frames = np.asarray(rec.extra["surface"]["frames"])
    assert frames.shape == (len(rec.samples), 11)
    # the frames lie on the cylinder (48 flat sides: radius between R cos(pi/48) and R)
    P = frames[:, 2:5]
    radius = np.hypot(P[:, 0], P[:, 1])
    assert (radius > R_MM * math.cos(math.pi / 48) - 1e-3).all() and (radius < R_MM + 1e-3).all()
    # the writing is centred under the brush and has the size asked for (arc length and height)
    touch = rec.samples[:, 2] < HAIR
    ang = np.arctan2(P[touch, 0], -P[touch, 1])
    arc = (ang.max() - ang.min()) * R_MM
    mid_arc = (ang.max() + ang.min()) / 2 * R_MM
    zs = P[touch, 2]
    assert (
        abs(mid_arc - a * R_MM) < 0.15 * size and abs((zs.max() + zs.min()) / 2 - z0) < 0.15 * size
    )
    assert 0.6 * size < arc < 1.0 * size and 0.6 * size < np.ptp(zs) < 1.0 * size
    # the texture shows the writing (compared below with a new simulation of the recording)
    shown = np.empty(len(st.paper_image.pixels), np.float32)
    st.paper_image.pixels.foreach_get(shown)
    assert ink(st.paper_image).max() > 0.3
    # the brush is keyframed over the surface: at sample i's frame, its pose is sample i's
    fps = sc.render.fps / sc.render.fps_base
    for i in (len(rec.samples) // 3, 2 * len(rec.samples) // 3):
        f = sc.frame_start + i * fps / rec.sample_rate_hz
        sc.frame_set(math.floor(f), subframe=f - math.floor(f))
        base, rot = ext().blender.surfaces.surface_pose(st, b.matrix_world)
        want_base, want_rot = ext().sim.surface.pose_from_sample(frames[i], rec.samples[i])
        np.testing.assert_allclose(base, want_base, atol=0.01)
        np.testing.assert_allclose(rot, want_rot, atol=1e-4)
    sc.frame_set(sc.frame_end)  # simulating the stored recording again: the same, bit for bit
    ext().blender.runtime.get().forget_playbacks()
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}
    again = np.empty(len(st.paper_image.pixels), np.float32)
    st.paper_image.pixels.foreach_get(again)
    np.testing.assert_array_equal(shown, again)
    # the ink is on the cylinder where the writing is, at its size
    tp = texels(sc)
    pts = tp.xyz[ink(st.paper_image).ravel()[tp.index] > 0.2]
    ang = np.arctan2(pts[:, 0], -pts[:, 1])
    assert abs((ang.max() + ang.min()) / 2 - a) * R_MM < 0.15 * size
    assert abs((pts[:, 2].max() + pts[:, 2].min()) / 2 - z0) < 0.15 * size
    assert (
        0.7 * size < np.ptp(ang) * R_MM < 1.1 * size and 0.7 * size < np.ptp(pts[:, 2]) < 1.1 * size
    )


@pytest.mark.slow
def test_imitate_picture_on_a_cylinder_is_laid_on_it_too(hb):
    """Imitate Picture writes through the same job: on a surface paper it is laid on it."""
    import json

    from sim.writing.outline import rasterise
    from tests.paths import ROOT

    cyl = cylinder()
    st = surface_scene(cyl, ppm=2.0)
    side, size_px = st.paper_width_mm, tuple(st.paper_image.size)
    char = json.loads((ROOT / "tests" / "data" / "unseen" / "王.json").read_text("utf-8"))
    pic = np.where(rasterise(char, 96), 0.05, 0.95)
    img = bpy.data.images.new("wang", 96, 96)
    rgba = np.ones((96, 96, 4), np.float32)
    rgba[..., :3] = pic[::-1, :, None]
    img.pixels.foreach_set(rgba.ravel())
    res = bpy.ops.hairy_brush.imitate_image(image="wang", size_mm=30.0, passes=1, detail=96)
    assert res == {"FINISHED"}
    assert st.paper_width_mm == side and tuple(st.paper_image.size) == size_px
    rec = ext().blender.recordings.recording_from_scene(bpy.context.scene)
    P = np.asarray(rec.extra["surface"]["frames"])[:, 2:5]
    assert np.abs(np.hypot(P[:, 0], P[:, 1]) - R_MM).max() < 0.2  # on the cylinder
    touch = P[rec.samples[:, 2] < HAIR]
    assert np.abs(touch[:, 0]).max() < 20.0 and (touch[:, 1] < 0).all()  # on the front
    assert ink(st.paper_image).max() > 0.3


def test_the_kept_surface_paper_is_the_one_a_fresh_session_would_build(hb):
    """The kept paper's chart offset depends on the recording's width in mm, not only on its
    texture's size: a recording 0.1 mm wider (same pixels) must not reuse the other's."""
    from sim.core.recording import Recording

    b = ext().blender.surfaces
    s = b.surf.surface_from_arrays(
        [[0, 0, 0], [10, 0, 0], [0, 10, 0]], [[0, 1, 2]], [[[0, 0], [1, 0], [0, 1]]]
    )
    a = Recording(np.zeros((1, 6)), width_mm=100.0, height_mm=100.0, px_per_mm=3.0)
    c = Recording(np.zeros((1, 6)), width_mm=100.1, height_mm=100.0, px_per_mm=3.0)
    assert (a.width_px, a.height_px) == (c.width_px, c.height_px)
    ext().blender.runtime.get().papers.clear()
    fresh = b.surface_paper_base(s, "d", c).offset
    ext().blender.runtime.get().papers.clear()
    b.surface_paper_base(s, "d", a)
    assert b.surface_paper_base(s, "d", c).offset == fresh
    assert b.surface_paper_base(s, "d", a).offset != fresh


@pytest.mark.slow
def test_write_character_on_a_surface_reports_progress_forwards_only(hb):
    """The flat writing takes the first part of the bar and laying/simulating on the surface
    the rest: the bar never runs backwards and ends at most full."""
    from tests.paths import ROOT

    cyl = cylinder()
    st = surface_scene(cyl, ppm=2.0)
    b = st.brush_object
    b.rotation_mode = "XYZ"
    b.location = (0.0, -(R_MM + HAIR + 5.0) / 1000, 0.0)
    b.rotation_euler = (math.pi / 2, 0.0, 0.0)
    mod = ext().blender.writing
    char = ext().sim.writing.hanzi.find_char(str(ROOT / "data" / "hanzi" / "十.json"))
    job = mod.WriteJob(bpy.context.scene, char, 30.0, 1)
    seen = []
    job._progress = lambda f, *details: seen.append((float(f), details))
    assert job.step(math.inf)
    fr = [f for f, _ in seen]
    assert fr == sorted(fr) and 0.0 <= fr[0] and fr[-1] <= 1.0
    first = next(i for i, (_, d) in enumerate(seen) if d and d[0] == "laying")
    assert 0 < first and max(fr[:first]) <= mod.WRITE_SHARE <= fr[first] and fr[-1] > 0.9


def test_frame_changes_read_the_paper_mesh_again_only_after_it_changed(hb, monkeypatch):
    """Following frames, the paper mesh is neither read nor hashed while it is unchanged; an
    edit (which the depsgraph reports) makes the next frame change use the mesh as it is."""
    sc = bpy.context.scene
    cyl = cylinder()
    st = surface_scene(cyl)
    key_around(st, np.linspace(-20, 20, 11), presses(11))
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    st.sync_frames = True
    b = ext().blender.surfaces
    reads = []
    real = b.mesh_arrays
    monkeypatch.setattr(b, "mesh_arrays", lambda obj: reads.append(obj.name) or real(obj))
    sc.frame_set(sc.frame_start)
    key = ext().blender.playback.playback_for(sc).key  # (read outside frame changes: counted)
    reads.clear()
    for f in (sc.frame_start + 3, sc.frame_end, sc.frame_start + 1):
        sc.frame_set(f)
    assert reads == [] and ext().blender.runtime.get().last_error == ""
    cyl.data.vertices[0].co.z += 0.001  # an edit the depsgraph reports
    bpy.context.view_layer.update()
    sc.frame_set(sc.frame_start + 2)
    assert "Cylinder" in reads
    with b.trusting_digests():
        assert ext().blender.playback.cache_key(sc) != key  # the new mesh's playback
    assert ext().blender.runtime.get().last_error == ""
