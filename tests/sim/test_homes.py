# SPDX-License-Identifier: GPL-3.0-or-later
"""One home for each default, and caches where they belong (issue 25): the fit's defaults are
FitSettings' and the command line shows them; the brush's calibrated response is kept on disk
only in a folder handed to the engine (the command line's: the platform's cache folder, or
$HAIRY_BRUSH_CACHE), never in the user's home unasked."""

import os
import subprocess
import sys

import numpy as np
import pytest

from sim.cli.main import _parser
from sim.core.recording import Recording
from sim.fitting.samples import TRAINING_SIZE_PX
from sim.fitting.search import FitSettings
from sim.writing import response as resp
from tests.paths import ROOT


def test_the_command_lines_fit_defaults_are_fitsettings():
    args = _parser().parse_args(["fit", "--chars", "一", "-o", "out.json"])
    want = FitSettings()
    for name in ("divisions", "rounds", "iterations", "workers", "max_grid"):
        assert getattr(args, name) == getattr(want, name), name
    assert args.size == TRAINING_SIZE_PX


def _template():
    return Recording(np.zeros((1, 6)), brush={"preset": "wolf_stiff"}, paper_preset="smooth")


@pytest.mark.slow
def test_the_response_is_kept_on_disk_only_in_the_folder_handed_in(tmp_path, monkeypatch):
    home = tmp_path / "home"
    monkeypatch.setenv("HOME", str(home))
    monkeypatch.setenv("XDG_CACHE_HOME", str(home / ".cache"))
    t = _template()
    monkeypatch.setattr(resp, "_CACHE", {})
    plain = resp.calibrate(t)  # no folder: measured, kept in the process only
    assert not home.exists()
    monkeypatch.setattr(resp, "_CACHE", {})
    kept = resp.calibrate(t, cache_dir=tmp_path / "cache")
    files = list((tmp_path / "cache").glob("response-*.json"))
    assert len(files) == 1 and not home.exists()
    monkeypatch.setattr(resp, "_CACHE", {})
    again = resp.calibrate(t, cache_dir=tmp_path / "cache")  # read back from the file
    for name in ("press_mm", "width_mm", "lag_mm", "speed_mm_s"):
        np.testing.assert_array_equal(getattr(plain, name), getattr(kept, name))
        np.testing.assert_array_equal(getattr(kept, name), getattr(again, name))


@pytest.mark.slow
def test_the_command_line_keeps_its_cache_in_hairy_brush_cache(tmp_path):
    env = {**os.environ, "HAIRY_BRUSH_CACHE": str(tmp_path / "cache"), "HOME": str(tmp_path)}
    env.pop("XDG_CACHE_HOME", None)
    out = tmp_path / "one.png"
    r = subprocess.run(
        [sys.executable, "-m", "sim", "write", str(ROOT / "data" / "hanzi" / "一.json")]
        + ["--size", "48", "--passes", "1", "-q", "-o", str(out)],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
    )
    assert r.returncode == 0, r.stderr
    assert out.is_file() and len(list((tmp_path / "cache").glob("response-*.json"))) == 1
    assert not (tmp_path / ".cache").exists()
