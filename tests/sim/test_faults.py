# SPDX-License-Identifier: GPL-3.0-or-later
"""Faults lose nothing (issue 30): the command line killed while it writes, on a full disk
(``ulimit -f``), under too little memory (``ulimit -v``), with damaged caches and NaN or huge
values, in child processes (tests/faults.py): never a traceback, never a hang, never a file
lost or half-written."""

from __future__ import annotations

import json
import os

import numpy as np
import pytest

from sim.core.files import WriteError, write_atomic
from sim.core.recording import from_dict
from sim.image.png import write_png
from tests.faults import leftovers, lost_files, run_sim, snapshot

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
