# SPDX-License-Identifier: GPL-3.0-or-later
"""Writing on 3D surfaces (issue 17), rendered with Cycles: the demo's 永 written by the brush
on a porcelain vase, and carved into a curved stone stele. Run after `bash scripts/demo.sh` (it
reads out/demo_recording.json); writes out/surface_vase.png (the front and, beside it, the back
where the texture's seam is: the ring stroke crosses it), out/surface_tablet.png, and
out/surface_cup.png (永 written on a cup by the Write Character operator itself, laid on the
surface under the brush; it needs no demo recording).

Each picture goes through the artist's path: the mesh is made the paper with
``setup(surface=True)``, the brush empty is keyframed along the character's strokes laid on the
surface (each flat sample's pose in the surface's frame at that place), ``bake_samples`` samples
it on the surface, ``simulate`` writes the ink into the mesh's texture, and for the stele
``relief(mode='CARVE')`` cuts it in.

    .venv/bin/python scripts/surface_pictures.py [vase|tablet|sphere|cup ...]"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts"))
import bench_live  # noqa: E402 - sets Blender's user folder before bpy is imported

bpy = bench_live.bpy
np = bench_live.np
OUT = ROOT / "out"


def revolved(name, radius, z0, z1, rings, around, angle=2 * math.pi, cap=False):
    """A surface of revolution about z (radius(z) in metres), UV u along the angle (its seam at
    the back), v along z; ``angle`` < 2 pi makes an open section (a curved stele's face)."""
    full = angle >= 2 * math.pi - 1e-9
    cols = around if full else around + 1
    zs = np.linspace(z0, z1, rings + 1)
    th = -angle / 2 + angle * np.arange(cols) / around if not full else None
    if full:
        th = math.pi + 2 * math.pi * np.arange(around) / around  # the seam at the back
    verts = [(radius(z) * math.sin(t), -radius(z) * math.cos(t), z) for z in zs for t in th]
    faces, uvs = [], []
    for j in range(rings):
        for i in range(around):
            i2 = (i + 1) % cols
            faces.append((j * cols + i, j * cols + i2, (j + 1) * cols + i2, (j + 1) * cols + i))
            u0, u1, v0, v1 = i / around, (i + 1) / around, j / rings, (j + 1) / rings
            uvs.append(((u0, v0), (u1, v0), (u1, v1), (u0, v1)))
    if cap:  # the bottom, a fan
        c = len(verts)
        verts.append((0.0, 0.0, z0))
        for i in range(around):
            faces.append((c, (i + 1) % cols, i))
            uvs.append(((0.5, 0.0), (0.5, 0.0), (0.5, 0.0)))  # no ink there: no UV area
    me = bpy.data.meshes.new(name)
    me.from_pydata(verts, [], faces)
    uv = me.uv_layers.new(name="UVMap")
    for face, co in zip(me.polygons, uvs, strict=True):
        for loop, c in zip(face.loop_indices, co, strict=True):
            uv.data[loop].uv = c
    me.shade_smooth()
    obj = bpy.data.objects.new(name, me)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def material(obj, color, roughness):
    mat = bpy.data.materials.new(obj.name)
    if mat.node_tree is None:
        mat.use_nodes = True
    bsdf = next(n for n in mat.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
    bsdf.inputs["Base Color"].default_value = (*color, 1.0)
    bsdf.inputs["Roughness"].default_value = roughness
    obj.data.materials.append(mat)


def laid_on(samples, radius, z_mid, size_mm):
    """World matrices of the brush for flat samples laid on the surface of revolution: x along
    the circle at the writing's height (arc length), y up; each sample's frame is the
    surface's own (normal, horizontal tangent), as sim.surface.pose_from_sample reads it."""
    ext = sys.modules[bench_live.ADDON]
    out = []
    r_mid = radius(z_mid) * 1000
    for s in samples:
        z = z_mid + (s[1] - size_mm / 2) / 1000
        th = (s[0] - size_mm / 2) / r_mid
        r = radius(z)
        slope = (radius(z + 1e-4) - radius(z - 1e-4)) / 2e-4
        p = np.array([r * math.sin(th), -r * math.cos(th), z]) * 1000
        n = np.array([math.sin(th), -math.cos(th), -slope])
        n /= np.linalg.norm(n)
        t = np.array([math.cos(th), math.sin(th), 0.0])
        frame = np.r_[s[:2], p, t, n]
        base, rot = ext.sim.surface.pose_from_sample(frame, s)
        m = np.eye(4)
        m[:3, :3], m[:3, 3] = rot, base / 1000
        out.append(m)
    return out


def keyframe(obj, matrices, rate_hz: float):
    """One key a sample (linear), location and quaternion, as keyframes.keyframe_samples does."""
    from mathutils import Matrix

    sc = bpy.context.scene
    fps = sc.render.fps / sc.render.fps_base
    frames = sc.frame_start + np.arange(len(matrices)) * fps / rate_hz
    obj.rotation_mode = "QUATERNION"
    loc, rot, prev = [], [], None
    for m in matrices:
        t, q, _s = Matrix(m.tolist()).decompose()
        if prev is not None and prev.dot(q) < 0:
            q.negate()
        loc.append(t[:])
        rot.append(q[:])
        prev = q
    for path, values in (("location", np.array(loc)), ("rotation_quaternion", np.array(rot))):
        for k in range(values.shape[1]):
            obj.keyframe_insert(path, index=k, frame=float(frames[0]))
        curves = {
            (fc.data_path, fc.array_index): fc
            for fc in sys.modules[bench_live.ADDON].blender.keyframes.fcurves(obj.animation_data)
        }
        for k in range(values.shape[1]):
            fc = curves[(path, k)]
            kp = fc.keyframe_points
            kp.add(len(values) - len(kp))
            kp.foreach_set("co", np.stack([frames, values[:, k]], 1).astype(np.float32).ravel())
            for p in kp:
                p.interpolation = "LINEAR"
            fc.update()
    sc.frame_end = int(math.ceil(frames[-1]))


def ring(rec, r_mm: float, dy_mm: float, turn: float = 1.06):
    """Flat samples of one stroke more than once around a circle of radius r_mm (laid_on wraps
    x around it), dy_mm below the character's middle: lands, goes round across the UV seam,
    lifts; a dip first (appended after the character's samples)."""
    touch = float(rec.samples[:, 2].max()) - 5.0  # the recording hovers 5 mm above touching
    n_go = int(2 * math.pi * r_mm * turn / 100.0 * rec.sample_rate_hz)  # 100 mm/s
    x0 = rec.width_mm / 2 - math.pi * r_mm * turn
    x = np.r_[np.full(30, x0), np.linspace(x0, x0 + 2 * math.pi * r_mm * turn, n_go)]
    x = np.r_[x, np.full(30, x[-1])]
    z = np.r_[np.linspace(touch + 5.0, touch - 7.0, 30), np.full(n_go, touch - 7.0)]
    z = np.r_[z, np.linspace(touch - 7.0, touch + 5.0, 30)]
    y = np.full(len(x), rec.height_mm / 2 - dy_mm)
    return np.stack([x, y, z, *np.zeros((3, len(x)))], axis=1)


def write_on(obj, ppm: float, radius, z_mid, ring_below_mm=None):
    """The demo's character written by the brush on ``obj`` (keyframed, baked, simulated);
    with ``ring_below_mm``, then a stroke round the mesh that far below it."""
    sc = bpy.context.scene
    assert bpy.ops.hairy_brush.import_recording(filepath=str(OUT / "demo_recording.json"))
    st = sc.hairy_brush
    rec = sys.modules[bench_live.ADDON].blender.recordings.recording_from_scene(sc)
    st.paper_color = (1.0, 1.0, 1.0)  # the mesh's own colour under the ink
    st.px_per_mm = ppm
    for o in sc.objects:
        o.select_set(o == obj)
    bpy.context.view_layer.objects.active = obj
    assert bpy.ops.hairy_brush.setup(surface=True) == {"FINISHED"}
    sc.frame_start = 1
    samples = rec.samples
    if ring_below_mm is not None:
        r_mm = radius(z_mid) * 1000
        samples = np.r_[samples, ring(rec, r_mm, ring_below_mm)]
    keyframe(st.brush_object, laid_on(samples, radius, z_mid, rec.width_mm), rec.sample_rate_hz)
    t0 = time.perf_counter()
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    t1 = time.perf_counter()
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}
    t2 = time.perf_counter()
    size = tuple(st.paper_image.size)
    print(f"{obj.name}: bake {t1 - t0:.1f} s, simulate {t2 - t1:.1f} s, image {size}")
    sc.frame_set(sc.frame_end)  # the render shows the artwork as at its frame: finished
    st.brush_object.hide_render = True
    for child in st.brush_object.children:
        child.hide_render = True
    return st


def stage(cam_loc, look_at, lens, sun_rot, energy, size, path, world=(0.6, 0.6, 0.62)):
    sc = bpy.context.scene
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    sc.collection.objects.link(cam)
    cam.location = cam_loc
    d = np.array(look_at) - np.array(cam_loc)
    from mathutils import Vector

    cam.rotation_euler = Vector(d.tolist()).to_track_quat("-Z", "Y").to_euler()
    cam.data.lens = lens
    sc.camera = cam
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = energy
    sun.data.angle = math.radians(3.0)
    sun.rotation_euler = sun_rot
    sc.collection.objects.link(sun)
    sc.world = bpy.data.worlds.new("World")
    sc.world.color = world
    sc.render.engine = "CYCLES"
    sc.cycles.samples, sc.cycles.device = 24, "CPU"
    sc.cycles.use_denoising = False
    sc.view_settings.view_transform = "Standard"
    sc.render.resolution_x, sc.render.resolution_y = size
    sc.render.filepath = str(path)
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    print(f"rendered {path} in {time.perf_counter() - t0:.1f} s")


def vase():
    bpy.ops.wm.read_homefile(use_empty=True)

    def radius(z):  # metres: a foot, a full belly and a neck
        u = min(max(z / 0.24, 0.0), 1.0)
        return 0.034 + 0.046 * math.sin(math.pi * (0.12 + 0.8 * u)) ** 1.6 - 0.012 * u

    obj = revolved("Vase", radius, 0.0, 0.24, 96, 160, cap=True)
    material(obj, (0.86, 0.88, 0.82), 0.25)
    st = write_on(obj, 6.0, radius, 0.115, ring_below_mm=62.0)
    st.brush_object.hide_viewport = True
    _floor(2.0, (0.35, 0.33, 0.3), 0.8)
    stage(
        (0.12, -0.62, 0.26),
        (0.0, 0.0, 0.115),
        70,
        (math.radians(55), 0.0, math.radians(-35)),
        3.0,
        (560, 640),
        OUT / "surface_vase.png",
    )
    cam = bpy.context.scene.camera  # the back, where the texture's seam is
    cam.location = (-0.1, 0.62, 0.2)
    from mathutils import Vector

    cam.rotation_euler = Vector((0.1, -0.62, -0.11)).to_track_quat("-Z", "Y").to_euler()
    bpy.data.objects["Sun"].rotation_euler = (math.radians(55), 0.0, math.radians(150))
    bpy.context.scene.render.filepath = str(OUT / "surface_vase_seam.png")
    bpy.ops.render.render(write_still=True)
    side_by_side(OUT / "surface_vase.png", OUT / "surface_vase_seam.png", OUT / "surface_vase.png")


def side_by_side(left, right, out):
    """Two renders of one size as one picture."""
    ext = sys.modules[bench_live.ADDON]
    a, b = (ext.sim.image.png.read_png(p)[..., :3] for p in (left, right))
    ext.sim.image.png.write_png(out, np.concatenate([a, b], axis=1))
    Path(right).unlink()


def tablet():
    bpy.ops.wm.read_homefile(use_empty=True)

    def radius(_z):  # a stele whose face is a section of a 0.4 m cylinder
        return 0.4

    obj = revolved("Stele", radius, 0.0, 0.16, 160, 140, angle=0.13 / 0.4)
    material(obj, (0.36, 0.35, 0.33), 0.85)
    st = write_on(obj, 8.0, radius, 0.08)
    for o in bpy.context.scene.objects:
        o.select_set(o == obj)
    assert bpy.ops.hairy_brush.relief(mode="CARVE", depth_mm=1.5, detail=2) == {"FINISHED"}
    solid = obj.modifiers.new("Thickness", "SOLIDIFY")
    solid.thickness = 0.03
    obj.data.materials[0].node_tree.nodes["HairyBrush Ink"].mute = True  # bare stone: carved only
    _floor(3.0, (0.25, 0.24, 0.22), 0.9)
    stage(
        (0.2, -0.8, 0.17),
        (0.0, -0.4, 0.075),
        62,
        (math.radians(70), 0.0, math.radians(-70)),
        4.0,
        (640, 560),
        OUT / "surface_tablet.png",
        world=(0.08, 0.08, 0.09),
    )
    return st


def sphere():
    """A UV sphere written on along its UV seam's meridian, over the pole, and round its
    equator across the seam: the strokes go on, unbroken, from one side of the seam to the
    other."""
    bpy.ops.wm.read_homefile(use_empty=True)
    bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=0.08)
    obj = bpy.context.active_object
    obj.data.shade_smooth()
    material(obj, (0.8, 0.78, 0.72), 0.5)
    sc = bpy.context.scene
    st = sc.hairy_brush
    st.brush_preset, st.px_per_mm, st.paper_color = "wolf_stiff", 5.0, (1.0, 1.0, 1.0)
    assert bpy.ops.hairy_brush.setup(surface=True) == {"FINISHED"}
    seam = seam_longitude(obj)
    hair = sys.modules[bench_live.ADDON].blender.presets.hair_length(st)
    first = meridian(seam, hair, 80.0)
    poses = first + meridian(seam, hair, 80.0, equator=True)
    sc.frame_start = 1
    keyframe(st.brush_object, poses, st.sample_rate_hz)
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    ext = sys.modules[bench_live.ADDON]
    rec = ext.blender.recordings.recording_from_scene(sc)  # a full dip before each stroke
    rec.dips = [ext.sim.core.recording.Dip(0), ext.sim.core.recording.Dip(len(first))]
    ext.blender.recordings.store_recording(st, rec)
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}
    sc.frame_set(sc.frame_end)
    st.brush_object.hide_render = True
    for child in st.brush_object.children:
        child.hide_render = True
    look = np.array([math.cos(seam), math.sin(seam), 0.0])  # from the seam's side, above
    side = np.array([-look[1], look[0], 0.0])
    cam = 0.42 * look + 0.12 * side + np.array([0.0, 0.0, 0.3])
    sun = look + side * 0.6 + np.array([0, 0, 0.8])
    stage(
        tuple(cam),
        (0.0, 0.0, 0.0),
        90,
        sun_direction(sun),
        3.5,
        (480, 480),
        OUT / "surface_sphere.png",
    )


def seam_longitude(obj) -> float:
    """The longitude (radians) of the UV sphere's seam: where its UVs' u is 0."""
    me = obj.data
    uv = me.uv_layers.active.data
    pts = [me.vertices[loop.vertex_index].co for loop in me.loops if uv[loop.index].uv[0] < 1e-4]
    p = [q for q in pts if abs(q.z) < 0.07]
    return math.atan2(p[0].y, p[0].x)


def meridian(lon, hair, speed_mm_s, equator=False, radius_mm=80.0, press=7.0, rate=120.0):
    """World matrices of the brush upright on the sphere: along the meridian at ``lon`` from
    40 deg south over the north pole and down the far side, or once round the equator across
    the seam; landing and lifting over 0.25 s."""
    arc = math.radians(250.0 if not equator else 390.0)
    n = int(arc * radius_mm / speed_mm_s * rate)
    ts = np.linspace(0.0, arc, n)
    lift = np.clip(np.minimum(ts, arc - ts) * radius_mm / speed_mm_s / 0.25, 0.0, 1.0)
    out = []
    for t, k in zip(ts, lift, strict=True):
        if equator:
            a = lon - math.radians(15.0) + t
            nrm = np.array([math.cos(a), math.sin(a), 0.0])
            x = np.array([-math.sin(a), math.cos(a), 0.0])
        else:
            lat = math.radians(-40.0) + t
            nrm = np.array([math.cos(lat) * math.cos(lon), math.cos(lat) * math.sin(lon),
                            math.sin(lat)])  # fmt: skip
            x = np.array([-math.sin(lon), math.cos(lon), 0.0])
        m = np.eye(4)
        m[:3, :3] = np.stack([x, np.cross(nrm, x), nrm], axis=1)
        m[:3, 3] = nrm * (radius_mm + hair + 5.0 - (press + 5.0) * k) / 1000
        out.append(m)
    return out


def sun_direction(towards) -> tuple:
    """Euler angles of a sun lamp shining from ``towards`` (a direction to the light)."""
    from mathutils import Vector

    return tuple(Vector(tuple(-np.asarray(towards))).to_track_quat("-Z", "Y").to_euler())


def cup():
    """永 written on a cup by Write Character itself (issue 17's follow-up): the brush empty is
    turned to face the cup's front, and the operator lays the writing on the surface there."""
    bpy.ops.wm.read_homefile(use_empty=True)

    def radius(z):  # metres: a tumbler widening a little to the lip
        return 0.04 + 0.006 * z / 0.11

    obj = revolved("Cup", radius, 0.0, 0.11, 40, 160, cap=True)
    material(obj, (0.9, 0.9, 0.86), 0.3)
    sc = bpy.context.scene
    st = sc.hairy_brush
    st.paper_color = (1.0, 1.0, 1.0)
    st.px_per_mm = 8.0
    for o in sc.objects:
        o.select_set(o == obj)
    bpy.context.view_layer.objects.active = obj
    assert bpy.ops.hairy_brush.setup(surface=True) == {"FINISHED"}
    b = st.brush_object
    b.location.z = 0.055  # half way up: the writing is centred under the brush
    t0 = time.perf_counter()
    res = bpy.ops.hairy_brush.write_character(character="永", size_mm=70.0, passes=2)
    assert res == {"FINISHED"}
    print(
        f"Cup: Write Character {time.perf_counter() - t0:.1f} s, image {tuple(st.paper_image.size)}"
    )
    sc.frame_set(sc.frame_end)
    b.hide_render = True
    for child in b.children:
        child.hide_render = True
    _floor(2.0, (0.35, 0.33, 0.3), 0.8)
    stage(
        (0.06, -0.36, 0.12),
        (0.0, 0.0, 0.058),
        60,
        (math.radians(55), 0.0, math.radians(-35)),
        3.0,
        (480, 480),
        OUT / "surface_cup.png",
    )


def _floor(size: float, colour, roughness: float):
    """A square floor under the object, in the scene."""
    floor = bpy.data.objects.new("Floor", _plane(size))
    bpy.context.scene.collection.objects.link(floor)
    material(floor, colour, roughness)
    return floor


def _plane(size):
    me = bpy.data.meshes.new("Floor")
    h = size / 2
    me.from_pydata([(-h, -h, 0), (h, -h, 0), (h, h, 0), (-h, h, 0)], [], [(0, 1, 2, 3)])
    return me


def main(argv) -> int:
    bench_live.install()
    which = argv or ["vase", "tablet", "sphere", "cup"]
    for name in which:
        {"vase": vase, "tablet": tablet, "sphere": sphere, "cup": cup}[name]()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
