# SPDX-License-Identifier: GPL-3.0-or-later
"""Issue 14, the artist's sidebar, with real bpy: the scene follows the settings, the sidebar
reads without the paper open, buttons say why they cannot run, and long jobs run in slices
that can be stopped (driven through their step logic: a modal operator needs a window)."""

from __future__ import annotations

import json
import math
import time
from types import SimpleNamespace

import numpy as np
import pytest

from tests.blender.helpers import (
    HAIR,
    ext,
    keyframe_stroke,
    mesh_without_uv,
    pixels,
    select_only,
    setup_scene,
)

bpy = pytest.importorskip("bpy")

from sim.core.recording import Recording, load  # noqa: E402
from sim.engine.simulation import Simulation  # noqa: E402


def paper_size_m(st):
    xs = [v.co.x for v in st.paper_object.data.vertices]
    ys = [v.co.y for v in st.paper_object.data.vertices]
    return max(xs) - min(xs), max(ys) - min(ys)


def brush_z(st):
    bpy.context.view_layer.update()
    s = ext().blender.transforms.sample_from_matrices(
        st, st.brush_object.matrix_world, st.paper_object.matrix_world
    )
    return float(s[2])


class Layout:
    """Records what a panel's draw() puts in the sidebar (no window to draw into)."""

    def __init__(self, log):
        self.log = log
        self.enabled = True
        self.use_property_split = False

    def prop(self, data, name, **kw):
        self.log.append(("prop", name, kw.get("text")))

    def prop_search(self, data, name, *args, **kw):
        self.log.append(("prop", name, None))

    def label(self, text="", **kw):
        self.log.append(("label", text, None))

    def operator(self, idname, **kw):
        self.log.append(("op", idname, kw.get("text")))
        return SimpleNamespace()

    def menu(self, idname, text="", **kw):
        self.log.append(("menu", idname, text))

    def row(self, **kw):
        return self

    column = box = row

    def separator(self, **kw):
        pass


def drawn(panel) -> list:
    log = []
    panel.draw(SimpleNamespace(layout=Layout(log)), bpy.context)
    return log


def names(log, kind):
    return [entry[1] for entry in log if entry[0] == kind]


# ----------------------------------------------------------------------------- 1. the scene follows
def test_the_paper_plane_follows_width_height_and_imports(hb, tmp_path):
    st = setup_scene(bpy)
    st.paper_width_mm, st.paper_height_mm = 150.0, 90.0
    assert paper_size_m(st) == pytest.approx((0.150, 0.090), abs=1e-6)
    rec = Recording(np.array([[10.0, 10.0, HAIR + 5, 0, 0, 0]] * 3), width_mm=64.0, height_mm=48.0)
    path = tmp_path / "r.json"
    rec.save(path)
    assert bpy.ops.hairy_brush.import_recording(filepath=str(path)) == {"FINISHED"}
    assert paper_size_m(st) == pytest.approx((0.064, 0.048), abs=1e-6)
    # the brush at the paper's centre is at the centre of the new size in engine mm
    s = ext().blender.transforms.sample_from_matrices(
        st, st.brush_object.matrix_world, st.paper_object.matrix_world
    )
    assert s[:2] == pytest.approx([32.0, 24.0], abs=1e-4)


def test_the_touching_height_is_shown_and_follows_the_brush_preset(hb):
    st = setup_scene(bpy)
    marker = ext().blender.scene_setup.hair_marker(st.brush_object)
    assert marker is not None and marker.empty_display_type == "SINGLE_ARROW"
    assert marker.empty_display_size == pytest.approx(HAIR / 1000)
    # the arrow points down from the base: its point is where the hair ends
    bpy.context.view_layer.update()
    down = np.array(marker.matrix_world.to_3x3()) @ np.array([0.0, 0.0, 1.0])
    assert down == pytest.approx([0.0, 0.0, -1.0], abs=1e-6)
    assert brush_z(st) == pytest.approx(HAIR + 5, abs=1e-4)
    keyframe_stroke(bpy, st, press=4.0)
    zs = [
        kp.co.y
        for fc in ext().blender.keyframes.fcurves(st.brush_object.animation_data)
        if fc.data_path == "location" and fc.array_index == 2
        for kp in fc.keyframe_points
    ]
    assert bpy.ops.hairy_brush.apply_preset(kind="brush", name="small_detail") == {"FINISHED"}
    small = 16.0
    assert st.touch_height_mm == pytest.approx(small)
    assert marker.empty_display_size == pytest.approx(small / 1000)
    zs_after = [
        kp.co.y
        for fc in ext().blender.keyframes.fcurves(st.brush_object.animation_data)
        if fc.data_path == "location" and fc.array_index == 2
        for kp in fc.keyframe_points
    ]
    # every key keeps its height relative to the touching height: presses stay presses
    assert np.array(zs_after) - np.array(zs) == pytest.approx((small - HAIR) / 1000, abs=1e-7)
    bpy.context.scene.frame_set(20)
    assert brush_z(st) == pytest.approx(small - 4.0, abs=1e-3)
    # the sidebar says where it touches and where the base is now
    labels = " ".join(names(drawn(bpy.types.HAIRY_BRUSH_PT_brush), "label"))
    assert "z = 16 mm" in labels and "4.0 mm pressed into" in labels


def test_bakes_that_draw_nothing_sensible_say_so_with_the_numbers(hb, capfd):
    st = setup_scene(bpy)
    sc = bpy.context.scene
    sc.frame_start, sc.frame_end = 1, 10
    # unanimated and hovering: nothing would come out, refused
    with pytest.raises(RuntimeError, match=r"does not move: all 46 samples .* 5.0 mm above"):
        bpy.ops.hairy_brush.bake_samples()
    assert st.recording is None
    # never touching: baked, with a warning naming the lowest point and the touching height
    keyframe_stroke(bpy, st, press=-2.0, frames=(1, 3, 8, 10))  # lowest 2 mm above the hair
    capfd.readouterr()
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    out = capfd.readouterr().out
    assert f"never touches the paper: its lowest point is z = {HAIR + 2:.1f} mm" in out
    assert f"touches at z = {HAIR:g} mm" in out
    # buried 10 mm through the paper
    keyframe_stroke(bpy, st, press=HAIR + 10.0, frames=(1, 3, 8, 10))
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    out = capfd.readouterr().out
    assert "goes 10.0 mm through the paper at frame 3" in out
    # a good stroke: no warning
    keyframe_stroke(bpy, st, press=4.0, frames=(1, 3, 8, 10))
    assert bpy.ops.hairy_brush.bake_samples() == {"FINISHED"}
    assert "Warning" not in capfd.readouterr().out


def test_dip_by_default_lands_at_the_current_frame(hb, capfd):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    sc = bpy.context.scene
    sc.frame_set(25)
    assert bpy.ops.hairy_brush.dip() == {"FINISHED"}
    rec = ext().blender.recordings.recording_from_scene(sc)
    want = ext().blender.frames.first_sample_from_frame(rec, sc, 25)
    assert 0 < want < len(rec.samples)
    assert want in [dp.before_sample for dp in rec.dips]
    # dipping after the last sample is still possible, and says it changes nothing recorded
    capfd.readouterr()
    assert bpy.ops.hairy_brush.dip(at="END") == {"FINISHED"}
    assert "changes nothing already recorded" in capfd.readouterr().out


def test_a_relative_sequence_folder_of_an_unsaved_file_is_refused(hb, tmp_path, monkeypatch):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st, frames=(1, 2, 3, 4))
    bpy.ops.hairy_brush.bake_samples()
    monkeypatch.chdir(tmp_path)
    assert not bpy.data.filepath and st.sequence_dir.startswith("//")
    with pytest.raises(RuntimeError, match="not saved yet: save the file first"):
        bpy.ops.hairy_brush.bake_sequence()
    assert list(tmp_path.iterdir()) == []  # nothing written where Blender was started


def test_a_mesh_without_uvs_is_skipped_and_the_others_get_the_ink(hb, capfd):
    st = setup_scene(bpy)
    bpy.ops.mesh.primitive_uv_sphere_add()
    sphere = bpy.context.active_object
    no_uv = mesh_without_uv(bpy)
    select_only(sphere, no_uv)
    capfd.readouterr()
    assert bpy.ops.hairy_brush.apply_to_mesh() == {"FINISHED"}
    assert "Skipped 'NoUV': no UV map" in capfd.readouterr().out
    mat = sphere.material_slots[0].material
    assert mat.node_tree.nodes["HairyBrush Ink"].image == st.paper_image
    assert not no_uv.data.materials  # untouched


# ----------------------------------------------------------------------------- 2. the sidebar
def test_one_label_per_setting_with_units_and_plain_quality_names(hb):
    props = bpy.types.Scene.bl_rna.properties["hairy_brush"].fixed_type.properties
    labels = [p.name for p in props if p.identifier != "rna_type"]
    assert len(labels) == len(set(labels)), labels
    assert not {"Brush", "Paper", "Ink"} & set(labels)
    for ident, unit in (
        ("paper_width_mm", "(mm)"),
        ("paper_height_mm", "(mm)"),
        ("px_per_mm", "(px/mm)"),
        ("paint_press_mm", "(mm)"),
        ("sample_rate_hz", "(Hz)"),
        ("paint_angle_step", "(°)"),
    ):
        assert props[ident].name.endswith(unit), ident
    q = bpy.types.Scene.bl_rna.properties["hairy_brush"].fixed_type.properties["quality"]
    qprops = [p for p in q.fixed_type.properties if p.identifier not in ("rna_type", "name")]
    assert len(qprops) == 11
    for p in qprops:
        assert not p.description.startswith("Eq"), p.identifier
        assert p.description.startswith(("Higher", "Lower")), p.identifier
        assert f"'{p.identifier}'" in p.description  # the paper's symbol follows
    assert props["sequence_dir"].subtype == "DIR_PATH"
    groups = ext().blender.presets.QUALITY_GROUPS
    assert [g[0] for g in groups] == ["Brush", "Ink in the Brush", "Paper"]
    grouped = [n for g in groups for n in g[2]]
    assert sorted(grouped) == sorted(p.identifier for p in qprops)
    assert {"pw", "eta"} <= set(groups[1][2])  # ink flow inside the brush, not the paper


def test_panels_follow_the_work_and_settings_sit_by_their_buttons(hb):
    setup_scene(bpy)
    order = ["paper", "brush", "ink", "write", "animation", "quality"]
    panels = [getattr(bpy.types, f"HAIRY_BRUSH_PT_{n}") for n in order]
    assert [p.bl_order for p in panels] == sorted(p.bl_order for p in panels)
    assert len({p.bl_order for p in panels}) == len(panels)
    logs = {n: drawn(p) for n, p in zip(order, panels, strict=True)}
    assert "hairy_brush.setup" in names(logs["paper"], "op")
    assert {"paper_width_mm", "px_per_mm", "paper_color", "paper_capacity"} <= set(
        names(logs["paper"], "prop")
    )
    assert "hairy_brush.dip" in names(logs["ink"], "op")
    assert {"ink_color", "dip_wetness", "dip_depth"} <= set(names(logs["ink"], "prop"))
    assert "hairy_brush.paint" in names(logs["write"], "op")
    assert {"paint_press_mm", "paint_angle_step"} <= set(names(logs["write"], "prop"))
    assert {"sample_rate_hz", "seed"} <= set(names(logs["animation"], "prop"))
    assert "hairy_brush.bake_samples" in names(logs["animation"], "op")
    assert "hairy_brush.fit_parameters" in names(logs["quality"], "op")
    for n in ("paper", "brush", "ink", "write", "animation"):
        assert "seed" not in names(logs[n], "prop") or n == "animation"


def test_preset_menus_name_the_active_preset_and_say_what_they_overwrite(hb, capfd):
    st = setup_scene(bpy)
    log = drawn(bpy.types.HAIRY_BRUSH_PT_brush)
    menu = [e for e in log if e[0] == "menu"]
    sim = ext().sim
    default = sim.core.params.load_preset("brush", sim.core.recording.DEFAULT_BRUSH).label
    assert menu == [("menu", "HAIRY_BRUSH_MT_brush_presets", default)]
    # the rest was written for the 'mixed' brush (hair 30 mm, 2 mm longer than wolf_stiff's,
    # so choosing wolf_stiff moves the empty): choose it first, as an artist would
    assert bpy.ops.hairy_brush.apply_preset(kind="brush", name="mixed") == {"FINISHED"}
    log = drawn(bpy.types.HAIRY_BRUSH_PT_brush)
    assert ("menu", "HAIRY_BRUSH_MT_brush_presets", "Mixed hair (jian hao)") in log
    cls = ext().operators.apply_preset.HAIRY_BRUSH_OT_apply_preset
    tip = cls.description(bpy.context, SimpleNamespace(kind="brush", name="wolf_stiff"))
    assert "hair length 28 mm" in tip and "Springiness" in tip
    tip = cls.description(bpy.context, SimpleNamespace(kind="ink", name="vermilion"))
    assert "Ink Colour, Ink Wetness and Dip Depth" in tip
    capfd.readouterr()
    assert bpy.ops.hairy_brush.apply_preset(kind="brush", name="wolf_stiff") == {"FINISHED"}
    out = capfd.readouterr().out
    assert "hair length 28 mm" in out and "moved down 2 mm" in out and "Springiness" in out
    log = drawn(bpy.types.HAIRY_BRUSH_PT_brush)
    assert ("menu", "HAIRY_BRUSH_MT_brush_presets", "Wolf hair, stiff (lang hao)") in log
    # "-" with none of the user's presets active says so instead of cancelling silently
    assert bpy.ops.hairy_brush.add_settings_preset(remove_active=True) == {"CANCELLED"}
    assert "' is not one of your presets" in capfd.readouterr().out
    # saving one names it on the menu; removing it names none again
    assert bpy.ops.hairy_brush.add_settings_preset(name="Wolf Test") == {"FINISHED"}
    assert bpy.types.HAIRY_BRUSH_MT_settings_presets.bl_label == "Wolf Test"
    assert bpy.ops.hairy_brush.add_settings_preset(remove_active=True) == {"FINISHED"}
    assert bpy.types.HAIRY_BRUSH_MT_settings_presets.bl_label == "Your Presets"
    assert st.brush_preset == "wolf_stiff"


def test_paper_colour_and_capacity_follow_the_preset_and_reach_the_engine(hb):
    st = setup_scene(bpy)
    sim = ext().sim
    paper = sim.core.recording.DEFAULT_PAPER  # the scene starts on the default paper
    assert paper != "smooth"  # so that choosing smooth below changes the values
    preset = sim.core.params.paper_from_preset(sim.core.params.load_preset("paper", paper))
    assert tuple(st.paper_color) == pytest.approx(preset.color)
    assert st.paper_capacity == pytest.approx(preset.capacity)
    st.paper_preset = "smooth"
    assert st.paper_capacity == pytest.approx(1000.0)
    st.paper_capacity = 0.3
    st.paper_color = (0.9, 0.8, 0.7)
    spec = ext().blender.recordings.settings_recording(bpy.context.scene).resolve()[2]
    assert spec.capacity == pytest.approx(0.3)
    assert spec.color == pytest.approx((0.9, 0.8, 0.7), abs=1e-6)


def test_paper_fibre_follows_the_preset_and_sits_by_ink_capacity(hb):
    st = setup_scene(bpy)
    sim = ext().sim
    fibre = {
        name: sim.core.params.paper_from_preset(sim.core.params.load_preset("paper", name)).fibre
        for name in ("raw_xuan", "sized_xuan", "smooth")
    }
    assert len(set(fibre.values())) == 3  # each choice below changes the value
    assert st.paper_fibre == pytest.approx(fibre[sim.core.recording.DEFAULT_PAPER])
    for name in ("smooth", "raw_xuan"):
        st.paper_preset = name
        assert st.paper_fibre == pytest.approx(fibre[name]), name
    # Apply Preset restores the preset's fibre also when the preset is already chosen
    st.paper_fibre = 0.05
    assert bpy.ops.hairy_brush.apply_preset(kind="paper", name="raw_xuan") == {"FINISHED"}
    assert st.paper_fibre == pytest.approx(fibre["raw_xuan"])
    prop = bpy.types.Scene.bl_rna.properties["hairy_brush"].fixed_type.properties["paper_fibre"]
    assert (prop.name, prop.subtype, prop.hard_min, prop.hard_max) == ("Fibre", "FACTOR", 0, 1)
    assert "0 = an even grey" in prop.description
    props = names(drawn(bpy.types.HAIRY_BRUSH_PT_paper), "prop")
    assert props.index("paper_fibre") == props.index("paper_capacity") + 1
    st.paper_fibre = 0.35
    assert ext().blender.recordings.settings_recording(bpy.context.scene).resolve()[
        2
    ].fibre == pytest.approx(0.35)


@pytest.mark.slow
def test_a_recordings_paper_fibre_is_imported_rendered_with_and_exported(hb, tmp_path):
    st = setup_scene(bpy)
    samples = [[60.0, 100.0, HAIR + 5, 0, 0, 0], [60.0, 100.0, HAIR - 4, 0, 0, 0]]
    samples += [[60.0 + i, 100.0, HAIR - 4, 0, 0, 0] for i in range(80)]
    samples += [[140.0, 100.0, HAIR + 5, 0, 0, 0]]
    rec = Recording(np.array(samples), px_per_mm=2.0, paper_preset="raw_xuan")
    rec.paper_overrides = {"fibre": 0.2}  # not raw xuan's own 0.4
    src = tmp_path / "fibre.json"
    rec.save(src)
    assert json.loads(src.read_text())["paper"]["fibre"] == pytest.approx(0.2)
    assert bpy.ops.hairy_brush.import_recording(filepath=str(src)) == {"FINISHED"}
    assert st.paper_preset == "raw_xuan" and st.paper_fibre == pytest.approx(0.2)
    # Blender renders it as `python -m sim render` does
    assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}
    want = Simulation(load(src)).run().paper.rgb()
    assert np.abs(pixels(st.paper_image)[..., :3] - want).max() <= 0.5 / 4095 + 1e-6
    out = tmp_path / "out.json"
    assert bpy.ops.hairy_brush.export_recording(filepath=str(out)) == {"FINISHED"}
    assert json.loads(out.read_text())["paper"]["fibre"] == pytest.approx(0.2)
    assert load(out).resolve()[2].fibre == pytest.approx(0.2)
    # the setting decides the image: the sheet's grain shows in the grey where the hair offers
    # little liquid (sim.paper.paper.paper_grain), more with a stronger fibre
    images = {}
    for fibre in (0.0, 0.9):
        st.paper_fibre = fibre
        assert bpy.ops.hairy_brush.simulate() == {"FINISHED"}
        blank = np.array(st.paper_color)
        images[fibre] = (blank - pixels(st.paper_image)[..., :3]).mean(axis=2)
    assert images[0.0].max() > 0.5  # the stroke inked
    changed = np.abs(images[0.9] - images[0.0])
    assert changed.max() > 0.01 and (changed > 0.01).sum() > 20, changed.max()


def test_the_recording_panel_reads_no_json(hb):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    n = len(json.loads(st.recording.as_string())["samples"])
    assert ("label", f"{n} samples, 1 dips", None) in drawn(bpy.types.HAIRY_BRUSH_PT_recording)
    st.recording.write("garbage that no parser would take")  # the count was kept on storing
    assert ("label", f"{n} samples, 1 dips", None) in drawn(bpy.types.HAIRY_BRUSH_PT_recording)


# ----------------------------------------------------------------------------- 3. polls
NEEDS = {
    "bake_samples": "No brush empty",
    "build_primitives": "No brush empty",
    "write_character": "No brush empty",
    "fit_parameters": "No brush empty",
    "simulate": "No recording yet",
    "dip": "No recording yet",
    "bake_sequence": "No recording yet",
    "export_recording": "No recording yet",
    "apply_to_mesh": "No paper image yet",
}


@pytest.mark.parametrize("op", sorted(NEEDS))
def test_buttons_that_cannot_run_are_greyed_out_and_say_why(hb, op):
    fn = getattr(bpy.ops.hairy_brush, op)
    assert not fn.poll()
    with pytest.raises(RuntimeError, match=NEEDS[op]):
        fn()


def test_every_operator_has_its_own_poll(hb):
    for cls in ext().operators.CLASSES:
        assert "poll" in vars(cls), cls.__name__


def test_polls_pass_once_there_is_something_to_work_on(hb):
    st = setup_scene(bpy)
    assert bpy.ops.hairy_brush.bake_samples.poll()
    assert not bpy.ops.hairy_brush.simulate.poll()
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    for op in ("simulate", "dip", "bake_sequence", "export_recording", "build_primitives"):
        assert getattr(bpy.ops.hairy_brush, op).poll(), op
    assert not bpy.ops.hairy_brush.apply_to_mesh.poll()  # nothing selected but the paper
    bpy.ops.mesh.primitive_uv_sphere_add()
    assert bpy.ops.hairy_brush.apply_to_mesh.poll()


# ----------------------------------------------------------------------------- 4. long jobs
def run_slices(job, budget=0.01, limit=60.0):
    fractions = []
    end = time.perf_counter() + limit
    while not job.step(budget):
        fractions.append(job.fraction)
        assert time.perf_counter() < end, "the job did not finish"
    return fractions


@pytest.mark.slow
def test_simulate_runs_in_slices_and_esc_puts_the_paper_back(hb):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    sc = bpy.context.scene
    before = pixels(st.paper_image)
    sim_mod = ext().operators.simulate
    job = sim_mod.SimulateJob(sc)
    job.step(0.0)  # a slice with no time left does at least nothing harmful
    for _ in range(3):
        job.step(0.005)
    assert 0 < job.fraction < 1
    sim_mod.SHOW_EVERY_S, old = 0.0, sim_mod.SHOW_EVERY_S
    try:
        job.step(0.005)  # shows the ink so far
    finally:
        sim_mod.SHOW_EVERY_S = old
    assert np.abs(pixels(st.paper_image) - before).max() > 0.05
    assert "sample" in job.status_line() and "Esc" in job.status_line()
    job.cancel()
    np.testing.assert_array_equal(pixels(st.paper_image), before)
    # to the end in slices: the same image as the engine's
    job = sim_mod.SimulateJob(sc)
    fractions = run_slices(job, budget=0.01)
    assert len(fractions) > 1 and fractions == sorted(fractions)
    level, message = job.finish(bpy.context)
    assert level == "INFO" and "Simulated" in message
    rec = ext().blender.recordings.recording_from_scene(sc)
    want = Simulation(rec).run().paper.rgb()
    assert np.abs(pixels(st.paper_image)[..., :3] - want).max() <= 0.5 / 4095 + 1e-6


def job_operator():
    """The modal job's own methods on a stand-in (no window to run a modal operator in)."""
    jobs = ext().blender.jobs

    class Runner:
        reports = []

        def report(self, kind, msg):
            self.reports.append((kind, msg))

    for name in ("begin_job", "modal", "_end", "_failed", "_finished"):
        setattr(Runner, name, getattr(jobs.JobOperator, name))
    return Runner()


@pytest.mark.slow
def test_the_modal_operator_runs_a_job_from_timer_events_and_stops_on_esc(hb):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st)
    bpy.ops.hairy_brush.bake_samples()
    sc = bpy.context.scene
    before = pixels(st.paper_image)
    jobs, simulate = ext().blender.jobs, ext().operators.simulate
    op = job_operator()
    op.begin_job(bpy.context, simulate.SimulateJob(sc))
    timer = SimpleNamespace(type="TIMER", value="NOTHING")
    jobs.SLICE_S, old = 0.005, jobs.SLICE_S
    try:
        assert op.modal(bpy.context, timer) == {"RUNNING_MODAL"}
        assert op.modal(bpy.context, SimpleNamespace(type="MOUSEMOVE")) == {"PASS_THROUGH"}
        assert op.modal(bpy.context, SimpleNamespace(type="ESC")) == {"CANCELLED"}
        assert op.reports[-1][0] == {"WARNING"} and "stopped" in op.reports[-1][1]
        np.testing.assert_array_equal(pixels(st.paper_image), before)
        op.begin_job(bpy.context, simulate.SimulateJob(sc))
        for _ in range(10_000):
            state = op.modal(bpy.context, timer)
            if state != {"RUNNING_MODAL"}:
                break
    finally:
        jobs.SLICE_S = old
    assert state == {"FINISHED"} and op.reports[-1][0] == {"INFO"}
    want = Simulation(ext().blender.recordings.recording_from_scene(sc)).run().paper.rgb()
    assert np.abs(pixels(st.paper_image)[..., :3] - want).max() <= 0.5 / 4095 + 1e-6


def test_bake_sequence_runs_in_slices(hb, tmp_path):
    st = setup_scene(bpy)
    keyframe_stroke(bpy, st, frames=(1, 3, 9, 10))
    bpy.ops.hairy_brush.bake_samples()
    job = ext().operators.bake_sequence.SequenceJob(bpy.context.scene, str(tmp_path / "seq"))
    fractions = run_slices(job, budget=0.001)
    assert len(fractions) >= 2
    assert sorted(p.name for p in (tmp_path / "seq").iterdir())[-1] == "paper_0010.png"
    assert len(job.written) == 10


@pytest.mark.slow
def test_write_character_in_a_worker_stops_cleanly_and_finishes(hb):
    from tests.paths import ROOT

    st = setup_scene(bpy, ppm=1.0)
    sc = bpy.context.scene
    char = ext().sim.writing.hanzi.find_char(str(ROOT / "data" / "hanzi" / "十.json"))
    write = ext().blender.writing
    before = (st.paper_width_mm, sc.frame_end, st.brush_object.animation_data)
    job = write.WriteJob(sc, char, 100.0, 1)
    assert job.step(0.01) is False  # started in a worker: Blender's thread is free
    time.sleep(0.2)
    job.cancel()  # a flag the worker reads at its next progress call
    job._thread.join(60.0)
    assert not job._thread.is_alive() and job.result is None and job.error is None
    assert (st.paper_width_mm, sc.frame_end, st.brush_object.animation_data) == before
    assert st.recording is None
    job = write.WriteJob(sc, char, 100.0, 1)
    fractions = run_slices(job, budget=0.05, limit=120.0)
    assert fractions and job.fraction == 1.0
    level, message = job.finish(bpy.context)
    assert level == "INFO" and "2 strokes" in message
    assert st.paper_width_mm == 100.0 and paper_size_m(st) == pytest.approx((0.1, 0.1))
    assert st.recording is not None and st.brush_object.animation_data.action is not None


@pytest.mark.slow
def test_fit_in_a_worker_reports_progress_and_sets_the_quality(hb):
    st = setup_scene(bpy, ppm=1.0)
    fit_mod = ext().operators.fit_parameters
    template = ext().blender.recordings.settings_recording(bpy.context.scene)
    char = ext().sim.writing.hanzi.find_char("一")
    settings = ext().sim.fitting.search.FitSettings(
        divisions=1, rounds=1, iterations=1, max_grid=2, workers=1, seed=0
    )

    def make():
        return ext().sim.fitting.samples.character_samples([char], 24, template, names=["一"])

    before = ext().blender.checks.quality_values(st)
    job = fit_mod.FitJob(st, make, settings, "Sliced Fit")
    job.step(0.01)
    job.cancel()
    assert ext().blender.checks.quality_values(st) == before
    job = fit_mod.FitJob(st, make, settings, "Sliced Fit")
    run_slices(job, budget=0.05, limit=300.0)
    assert "round" in job.status
    level, message = job.finish(bpy.context)
    assert level == "INFO" and "Eq. 28" in message
    assert ext().blender.checks.quality_values(st) != before
    assert math.isfinite(st.quality.e)
