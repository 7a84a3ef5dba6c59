# SPDX-License-Identifier: GPL-3.0-or-later
"""Faults lose nothing (issue 30): the command line killed while it writes, on a full disk
(``ulimit -f``), under too little memory (``ulimit -v``), with damaged caches and NaN or huge
values, in child processes (tests/faults.py): never a traceback, never a hang, never a file
lost or half-written."""

from __future__ import annotations

import json
import os
import shutil

import numpy as np
import pytest

from sim.core.files import WriteError, write_atomic
from sim.core.recording import RecordingError, from_dict
from sim.engine.checkpoints import CacheError, load_checkpoints, save_checkpoints
from sim.image.png import write_png
from tests.faults import (
    child_env,
    disk_full_at,
    group_members,
    leftovers,
    lost_files,
    run_sim,
    snapshot,
)
from tests.paths import ROOT

REC = {
    "format": "hairy-brush-recording",
    "version": 1,
    "paper": {"width_mm": 60, "height_mm": 40, "px_per_mm": 4, "preset": "raw_xuan"},
    "sample_rate_hz": 120,
    "seed": 3,
    "samples": [
        [10, 20, 34, 0, 0, 0],
        [12, 20, 24, 0, 0, 0],
        [30, 21, 24, 0, 0, 0],
        [50, 22, 34, 0, 0, 0],
    ],
}


def rendered(tmp_path):
    """A recording, a good PNG rendered from it and a good recording file beside it."""
    rec = tmp_path / "rec.json"
    rec.write_text(json.dumps(REC), encoding="utf-8")
    out = tmp_path / "out.png"
    write_png(out, np.full((40, 60, 3), 0.5))
    (tmp_path / "keep.json").write_text(json.dumps(REC), encoding="utf-8")
    return rec, out


# ------------------------------------------------------------------ 1. atomic files
def test_write_atomic_keeps_the_previous_file_when_the_writer_fails(tmp_path):
    p = tmp_path / "f.bin"
    p.write_bytes(b"old")

    def half(f):
        f.write(b"new and half")
        raise OSError(28, "No space left on device")

    with pytest.raises(WriteError, match="cannot write .*f.bin: No space left on device"):
        write_atomic(p, half)
    assert p.read_bytes() == b"old" and not leftovers(tmp_path)
    with pytest.raises(ZeroDivisionError):
        write_atomic(p, lambda f: f.write(b"x") and 1 / 0)
    assert p.read_bytes() == b"old" and not leftovers(tmp_path)
    write_atomic(p, "new")
    assert p.read_text() == "new" and not leftovers(tmp_path)


def test_write_atomic_keeps_permissions_and_writes_through_a_link(tmp_path):
    p = tmp_path / "f.txt"
    p.write_text("old")
    os.chmod(p, 0o640)
    link = tmp_path / "link.txt"
    link.symlink_to(p)
    write_atomic(link, "new")
    assert link.is_symlink() and p.read_text() == "new"
    assert (os.stat(p).st_mode & 0o777) == 0o640
    with pytest.raises(WriteError, match="it is a folder"):
        write_atomic(tmp_path, "x")


@pytest.mark.parametrize("file_size", [0, 1024])
def test_a_render_killed_at_the_moment_it_writes_leaves_the_previous_png(tmp_path, file_size):
    rec, out = rendered(tmp_path)
    before = snapshot(tmp_path)
    run = run_sim(
        ["render", rec, "-o", out, "-q"], file_size=file_size, killed_at_write=True, seconds=60
    )
    assert run.code == -25, run.err  # SIGXFSZ: killed at the write that passed the limit
    assert lost_files(before, tmp_path) == []
    assert out.read_bytes() == before["out.png"]


def test_a_full_disk_keeps_the_previous_png_with_one_message(tmp_path):
    rec, out = rendered(tmp_path)
    before = snapshot(tmp_path)
    run = run_sim(["render", rec, "-o", out, "-q"], file_size=1024, seconds=60)
    assert run.code == 2 and not run.traceback, run.err
    assert run.message == (
        f"error: cannot write {out}: File too large (any earlier file there is kept)"
    ), run.err
    assert snapshot(tmp_path) == before  # nothing lost, no temporary file left


def test_a_recording_saved_on_a_full_disk_keeps_the_previous_one(tmp_path):
    import resource

    p = tmp_path / "r.json"
    from_dict(REC).save(p)
    before = p.read_bytes()
    longer = from_dict({**REC, "samples": REC["samples"] * 100})
    old = resource.getrlimit(resource.RLIMIT_FSIZE)
    resource.setrlimit(resource.RLIMIT_FSIZE, (len(before) + 10, old[1]))  # EFBIG, not a kill:
    try:  # Python ignores SIGXFSZ
        with pytest.raises(WriteError, match="File too large"):
            longer.save(p)
    finally:
        resource.setrlimit(resource.RLIMIT_FSIZE, old)
    assert p.read_bytes() == before and not leftovers(tmp_path)
    longer.extra["bad"] = float("nan")  # never written as JSON that no reader takes
    with pytest.raises(ValueError):
        longer.save(p)
    assert p.read_bytes() == before and not leftovers(tmp_path)


@pytest.mark.slow
def test_write_set_on_a_full_disk_keeps_the_previous_files(tmp_path):
    out = tmp_path / "set"
    out.mkdir()
    args = ["write-set", "一", "--size", "64", "--passes", "1", "--workers", "1", "-q"]
    assert run_sim([*args, "--out-dir", out]).code == 0
    before = snapshot(out)
    assert set(before) == {"000.png", "000.json"}
    (out / "000.png").write_bytes(b"\x89PNG old")  # told apart from a new one
    before = snapshot(out)
    run = run_sim([*args, "--seed", 5, "--out-dir", out], file_size=len(before["000.json"]) // 2)
    assert run.code == 2 and "cannot write" in run.message and not run.traceback, run.err
    assert json.loads((out / "000.json").read_bytes()) == json.loads(before["000.json"])
    assert not leftovers(out)


# ------------------------------------------------------------------ 2. the farm cache
def timeline_of(samples, every=2):
    from sim.engine.simulation import Simulation
    from sim.engine.timeline import Timeline

    return Timeline(Simulation(from_dict({**REC, "samples": samples})), every=every)


STROKE_A = [[10, 20, 34, 0, 0, 0]] + [[10 + 2 * i, 20, 24, 0, 0, 0] for i in range(20)]
STROKE_B = [[10, 30, 34, 0, 0, 0]] + [[10 + 2 * i, 30 - i / 2, 23, 0, 0, 0] for i in range(20)]


def baked(samples, folder, key):
    tl = timeline_of(samples)
    tl.seek(len(samples))
    save_checkpoints(tl, folder, key)
    return tl


def same_paper(a, b) -> bool:
    return all(np.array_equal(getattr(a.paper, k), getattr(b.paper, k)) for k in ("ink", "wet"))


def test_a_cache_is_used_only_for_its_key_and_every_file_is_checked(tmp_path):
    folder = tmp_path / "cache"
    made = baked(STROKE_A, folder, "A")
    fresh = timeline_of(STROKE_A)
    assert load_checkpoints(fresh, folder, "A") == len(made.snaps) > 5
    assert same_paper(fresh.seek(15), timeline_of(STROKE_A).seek(15))
    for key, damage, says in [
        ("B", None, "another recording or other settings"),
        ("A", lambda p: p.write_bytes(p.read_bytes()[: p.stat().st_size // 2]), "not the size"),
        ("A", lambda p: p.write_bytes(b"\0" * p.stat().st_size), "is damaged"),
        ("A", lambda p: p.unlink(), "missing"),
    ]:
        damaged = tmp_path / f"damaged-{says[:8]}"
        shutil.copytree(folder, damaged)
        if damage is not None:
            damage(sorted(damaged.glob("checkpoint_*.npz"))[3])
        fresh = timeline_of(STROKE_A)
        with pytest.raises(CacheError, match=says):
            load_checkpoints(fresh, damaged, key)
        assert list(fresh.snaps) == [0]  # nothing was taken from it


def test_a_checkpoint_from_another_bake_is_refused(tmp_path):
    baked(STROKE_A, tmp_path / "a", "A")
    baked(STROKE_B, tmp_path / "b", "B")
    name = sorted((tmp_path / "a").glob("checkpoint_*.npz"))[2].name
    (tmp_path / "a" / name).write_bytes((tmp_path / "b" / name).read_bytes())
    m = json.loads((tmp_path / "a" / "manifest.json").read_text())
    for entry in m["files"]:  # even with the manifest's sizes made to match
        entry["bytes"] = (tmp_path / "a" / entry["name"]).stat().st_size
    (tmp_path / "a" / "manifest.json").write_text(json.dumps(m))
    with pytest.raises(CacheError, match=f"{name} belongs to another cache"):
        load_checkpoints(timeline_of(STROKE_A), tmp_path / "a", "A")


@pytest.mark.parametrize("fail_at", ["checkpoint_00000006", "manifest", "swap"])
def test_a_bake_that_fails_keeps_the_previous_cache_whole(tmp_path, monkeypatch, fail_at):
    """Issue 30's lie: bake A, bake B failing (disk full) - the folder is A's cache, whole, or
    B's, never B's files under A's manifest."""
    from sim.engine import checkpoints

    folder = tmp_path / "cache"
    baked(STROKE_A, folder, "A")
    before = snapshot(folder)
    if fail_at == "swap":  # the old cache moved aside, then the new one cannot take its place
        real, calls = os.rename, []

        def rename(a, b):
            calls.append(b)
            return full_disk() if len(calls) == 2 else real(a, b)

        monkeypatch.setattr(checkpoints.os, "rename", rename)
    with disk_full_at(fail_at), pytest.raises(OSError, match="No space left on device"):
        baked(STROKE_B, folder, "B")
    monkeypatch.undo()
    assert snapshot(folder) == before
    assert [p.name for p in tmp_path.iterdir()] == ["cache"]  # no half-made folder left
    with pytest.raises(CacheError):
        load_checkpoints(timeline_of(STROKE_B), folder, "B")
    fresh = timeline_of(STROKE_A)
    load_checkpoints(fresh, folder, "A")
    for target in (7, 12, 20):
        assert same_paper(fresh.seek(target), timeline_of(STROKE_A).seek(target))


def full_disk():
    raise OSError(28, "No space left on device")


# ------------------------------------------------------------------ 3. the calibration cache
def response_file(template, cache_dir):
    from sim.writing import response

    key = response._cache_key(template, 60.0, 11, response.CAL_PPM)
    return response._cache_file(key, cache_dir)


def a_good_response(template) -> dict:
    """What calibrate writes: the calibration's 11 depths, non-decreasing widths, lags."""
    from sim.writing.response import CAL_DEPTHS

    hair = template.resolve()[1].hair_length_mm
    press = np.linspace(*CAL_DEPTHS, 11) * hair
    return {
        "press": press.tolist(),
        "width": np.linspace(0.1, 6.5, 11).tolist(),
        "lag": (0.2 + 0.23 * press).tolist(),
        "v": 60.0,
    }


def poisons(good: dict):
    yield "short press list", {**good, "press": good["press"][:4]}
    yield "string v", {**good, "v": "60"}
    yield "boolean v", {**good, "v": True}
    yield "NaN widths", {**good, "width": [float("nan")] * 11}
    yield "infinite lag", {**good, "lag": [float("inf")] + good["lag"][1:]}
    yield "empty arrays", {"press": [], "width": [], "lag": [], "v": 60.0}
    yield "widths shrinking", {**good, "width": good["width"][::-1]}
    yield "negative width", {**good, "width": [-1.0] + good["width"][1:]}
    yield "another brush's presses", {**good, "press": [p * 1.5 for p in good["press"]]}
    yield "nested widths", {**good, "width": [[w] for w in good["width"]]}
    yield "huge number", {**good, "lag": [10**400] + good["lag"][1:]}
    yield "missing field", {k: v for k, v in good.items() if k != "lag"}
    yield "a list", [good]
    yield "not JSON", "{press: [1, 2"
    yield "binary", b"\x89PNG\r\n\x1a\n\x00\x00"
    yield "deep", "[" * 100_000 + "]" * 100_000


def test_a_poisoned_calibration_cache_is_measured_again(tmp_path, monkeypatch):
    from sim.writing import response

    template = from_dict(REC)
    path = response_file(template, tmp_path)
    good = a_good_response(template)
    measured = response.Response(*(np.array(good[k]) for k in ("press", "width", "lag")), 60.0)
    calls = []
    monkeypatch.setattr(response, "_calibrate", lambda *a: calls.append(a) or measured)
    path.write_text(json.dumps(good))
    monkeypatch.setattr(response, "_CACHE", {})
    np.testing.assert_array_equal(
        response.calibrate(template, cache_dir=tmp_path).width_mm, good["width"]
    )
    assert calls == []  # a sound file is used as it is
    for name, bad in poisons(good):
        monkeypatch.setattr(response, "_CACHE", {})
        data = bad if isinstance(bad, bytes) else (bad if isinstance(bad, str) else json.dumps(bad))
        path.write_bytes(data if isinstance(data, bytes) else data.encode())
        got = response.calibrate(template, cache_dir=tmp_path)
        assert got is measured and len(calls) == 1, name  # measured again, once
        assert json.loads(path.read_text()) == good, name  # and the file made sound
        calls.clear()


@pytest.mark.slow
def test_sim_write_with_a_poisoned_calibration_cache_writes(tmp_path):
    cache = tmp_path / "cache"
    argv = ["write", "一", "--size", "64", "--passes", "1", "-q", "-o", tmp_path / "o.png"]
    env = child_env(HAIRY_BRUSH_CACHE=cache)
    assert run_sim(argv, env=env).code == 0
    (path,) = cache.glob("response-*.json")
    good = json.loads(path.read_text())
    assert good["v"] == 60.0
    path.write_text(json.dumps({**good, "press": good["press"][:3]}))  # a short press list
    run = run_sim(argv, env=env)
    assert run.code == 0 and not run.traceback, run.err
    assert json.loads(path.read_text()) == good


# ------------------------------------------------------------------ 4. low memory
MB = 2**20


def test_the_sweep_needs_no_blas_workspace(monkeypatch):
    """The sweep's interpolation matrix comes from the engine's own elimination, not LAPACK
    (whose OpenBLAS workspace spins for ever under a memory limit)."""
    from sim.core import nurbs

    def no_lapack(*_a, **_kw):
        raise AssertionError("LAPACK called")

    monkeypatch.setattr(np.linalg, "inv", no_lapack)
    monkeypatch.setattr(np.linalg, "solve", no_lapack)
    layout = nurbs.SweepLayout()
    collocation = nurbs.bspline_basis(layout.knots_s, 3, layout.station_u)
    np.testing.assert_allclose(layout.interp @ collocation, np.eye(layout.stations), atol=1e-13)


@pytest.mark.parametrize(
    "argv, memory, says",
    [
        (["render", "examples/strokes.json"], 100 * MB, "not enough memory to start"),
        (["render", "examples/strokes.json", "--px-per-mm", "36"], 200 * MB, "2880 x 2880 px"),
        (["write", "一", "--size", "64", "--passes", "1"], 100 * MB, "not enough memory"),
    ],
)
def test_too_little_memory_ends_in_one_line_saying_how_much(tmp_path, argv, memory, says):
    run = run_sim([*argv, "-q", "-o", tmp_path / "o.png"], memory=memory, seconds=60)
    assert not run.hung and not run.traceback, run.err  # it used to spin at 100% CPU for ever
    assert run.code == 3 and says in run.message and "MB" in run.message, run.err
    assert not (tmp_path / "o.png").exists()


@pytest.mark.slow
def test_memory_running_out_anywhere_in_a_render_is_one_message(tmp_path):
    """Limits from too little to enough: each run ends in the image or one line, never a
    traceback or a hang, and the previous image stays whole."""
    out = tmp_path / "o.png"
    write_png(out, np.zeros((4, 4, 3)))
    before = out.read_bytes()
    codes = []
    for memory in range(100 * MB, 260 * MB, 20 * MB):  # from the start guard (about 135 MB) up
        argv = ["render", "examples/strokes.json", "--px-per-mm", "8", "-q", "-o", out]
        run = run_sim(argv, memory=memory, seconds=90)
        assert not run.hung and not run.traceback, (memory, run.err)
        assert run.code in (0, 3) and (run.code == 0 or "memory" in run.message), run.err
        codes.append(run.code)
        if run.code:
            assert out.read_bytes() == before
    assert 3 in codes and 0 in codes


def test_a_memory_error_anywhere_is_one_line_with_the_size_needed(monkeypatch, capsys):
    from sim.cli import main as cli

    def huge(_args):
        return np.ones((2**62,), dtype=np.uint8)  # numpy's MemoryError, with the size

    monkeypatch.setattr(cli, "cmd_render", huge)
    monkeypatch.setattr(cli, "_parser", lambda: _one_command(lambda a: cli.cmd_render(a)))
    assert cli.main(["x"]) == 3
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("error: not enough memory (")
    assert f"({2**62 / MB:.0f} MB more were needed at once)" in err


def _one_command(func):
    import argparse

    ap = argparse.ArgumentParser()
    ap.add_argument("x")
    ap.set_defaults(func=func)
    return ap


# ------------------------------------------------------------------ 6. a huge rotation
@pytest.mark.parametrize("r", [1e308, -1e7, 1_000_000.5])
def test_a_huge_rotation_is_refused_by_name(tmp_path, r):
    samples = [row[:5] + [r if i == 2 else 0] for i, row in enumerate(REC["samples"])]
    with pytest.raises(RecordingError, match=r"'samples\[2\]\[5\]' \(rotation r\)"):
        from_dict({**REC, "samples": samples})
    p = tmp_path / "r.json"
    p.write_text(json.dumps({**REC, "samples": samples}))
    run = run_sim(["render", p, "-q", "-o", tmp_path / "o.png"], seconds=60)
    assert run.code == 2 and "(rotation r)" in run.message and not run.traceback, run.err


def test_a_rotation_that_winds_on_renders_as_its_remainder():
    from sim.engine.simulation import Simulation

    turns = [row[:5] + [row[5] + 360.0 * 2000] for row in REC["samples"]]
    wound = Simulation(from_dict({**REC, "samples": turns})).run()
    plain = Simulation(from_dict(REC)).run()
    assert np.isfinite(wound.paper.ink).all()
    assert np.abs(wound.paper.ink - plain.paper.ink).max() < 1e-3


# ------------------------------------------------------------------ 8. messages
@pytest.mark.parametrize(
    "argv, says",
    [
        (["render", "REC", "-o", ""], "argument -o/--output: is empty"),
        (["render", "", "-o", "OUT"], "argument recording: is empty"),
        (["write", "一", "--quality", "", "-o", "OUT"], "argument --quality: is empty"),
        (["write", "一", "--data", " ", "-o", "OUT"], "argument --data: is empty"),
        (["write-set", "一", "--out-dir", ""], "argument --out-dir: is empty"),
        (["imitate", "", "-o", "OUT"], "argument image: is empty"),
        (["write", "一", "--size-mm", "nan", "-o", "OUT"], "argument --size-mm: must lie in"),
        (["render", "REC", "-o", "NOWHERE/o.png"], "no such folder"),
    ],
)
def test_messages_name_the_option_and_leak_nothing(tmp_path, capsys, argv, says):
    from sim.cli.main import main

    rec, _ = rendered(tmp_path)
    subst = {"REC": rec, "OUT": tmp_path / "o.png", "NOWHERE/o.png": tmp_path / "no" / "o.png"}
    try:
        code = main([str(subst.get(a, a)) for a in argv])
    except SystemExit as exc:
        code = exc.code
    err = capsys.readouterr().err
    assert code == 2 and says in err, err
    assert "Errno" not in err and "Traceback" not in err and "''" not in err


# ------------------------------------------------------------------ a killed command's workers
@pytest.mark.slow
def test_a_killed_command_leaves_no_pool_worker_waiting_for_ever():
    """write-set and fit run their work in a process pool; killed (SIGKILL, nothing told the
    pool), the parent used to leave its workers waiting for tasks for ever."""
    import subprocess
    import sys
    import time

    script = (
        "import time; from sim.fitting.cluster import map_tasks; map_tasks(time.sleep, [60], 1)"
    )
    p = subprocess.Popen([sys.executable, "-c", script], cwd=ROOT, start_new_session=True)
    try:
        end = time.perf_counter() + 30
        while len(group_members(p.pid)) < 2 and time.perf_counter() < end:
            time.sleep(0.1)
        assert len(group_members(p.pid)) == 2  # the command and its pool's worker
        p.kill()
        p.wait()
        end = time.perf_counter() + 5
        while group_members(p.pid) and time.perf_counter() < end:
            time.sleep(0.1)
        assert group_members(p.pid) == []
    finally:
        for pid in group_members(p.pid):
            os.kill(pid, 9)


def test_a_checkpoint_with_a_paper_stroke_that_is_not_one_is_refused(tmp_path):
    folder = tmp_path / "cache"
    baked(STROKE_A, folder, "A")
    path = sorted(folder.glob("checkpoint_*.npz"))[2]
    with np.load(path, allow_pickle=False) as z:
        arrays = {k: z[k] for k in z.files}
    meta = json.loads(bytes(arrays["meta"]).decode("utf-8"))
    meta["paper_stroke"] = [1, 2, "three"]
    arrays["meta"] = np.frombuffer(json.dumps(meta).encode("utf-8"), dtype=np.uint8)
    with open(path, "wb") as f:
        np.savez_compressed(f, **arrays)
    m = json.loads((folder / "manifest.json").read_text())
    for entry in m["files"]:
        entry["bytes"] = (folder / entry["name"]).stat().st_size
    (folder / "manifest.json").write_text(json.dumps(m))
    with pytest.raises(CacheError, match="paper stroke that is not one"):
        load_checkpoints(timeline_of(STROKE_A), folder, "A")
