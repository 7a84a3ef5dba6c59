# SPDX-License-Identifier: GPL-3.0-or-later
import copy
import json
import subprocess
import sys

import numpy as np
import pytest

from sim.core.params import PRESET_DIR, ParameterError, QualityParams, load_preset, preset_names
from sim.core.recording import RecordingError, from_dict, load, loads
from tests.paths import ROOT

GOOD = {
    "format": "hairy-brush-recording",
    "version": 1,
    "paper": {"width_mm": 60, "height_mm": 40, "px_per_mm": 4, "preset": "raw_xuan"},
    "brush": {"preset": "mixed"},
    "ink": {"preset": "sumi_black"},
    "quality": {"e": 0.6},
    "sample_rate_hz": 120,
    "seed": 3,
    "samples": [[10, 20, 34, 0, 0, 0], [12, 20, 24, 0, 0, 0], [20, 20, 24, 0, 0, 0]],
    "dips": [{"before_sample": 0, "depth": 0.6, "color": [0, 0, 0], "wetness": 0.9}],
}


def bad(path, value=None, delete=False):
    d = copy.deepcopy(GOOD)
    *head, last = path
    node = d
    for k in head:
        node = node[k]
    if delete:
        del node[last]
    else:
        node[last] = value
    return d


def test_good_recording_roundtrips(tmp_path):
    rec = from_dict(GOOD)
    assert rec.width_px == 240 and rec.height_px == 160
    q, geom, paper, ink = rec.resolve()
    assert q.e == 0.6 and q.ab == load_preset("paper", "raw_xuan").data["quality"]["ab"]
    p = tmp_path / "r.json"
    rec.save(p)
    again = load(p)
    assert np.array_equal(again.samples, rec.samples) and again.seed == 3


def test_optional_sections_take_defaults():
    d = {k: v for k, v in GOOD.items() if k not in ("brush", "ink", "quality", "dips")}
    d["paper"] = {k: v for k, v in GOOD["paper"].items() if k != "preset"}
    rec = from_dict(d)
    (dip,) = rec.dips_or_default()
    assert dip.depth == 1.0 and dip.color == (0.0, 0.0, 0.0)  # a full dip in black ink


@pytest.mark.parametrize(
    "doc, field",
    [
        (bad(["format"], "png"), "format"),
        (bad(["version"], 7), "version"),
        (bad(["paper"], delete=True), "paper"),
        (bad(["paper", "px_per_mm"], delete=True), "paper.px_per_mm"),
        (bad(["paper", "width_mm"], -5), "paper.width_mm"),
        (bad(["paper", "px_per_mm"], 150), "too large"),
        (bad(["paper", "preset"], "cardboard"), "cardboard"),
        (bad(["brush", "preset"], "toothbrush"), "toothbrush"),
        (bad(["quality", "e"], 1.5), "quality.e"),
        (bad(["quality", "zz"], 0.5), "quality.zz"),
        (bad(["samples"], delete=True), "samples"),
        (bad(["samples"], []), "samples"),
        (bad(["samples", 1], [1, 2, 3]), "samples[1]"),
        (bad(["samples", 2, 4], "x"), "samples[2][4]"),
        (bad(["samples", 0, 1], float("nan")), "samples[0][1]"),
        (bad(["samples", 0, 3], 120.0), "samples[0]"),
        (bad(["sample_rate_hz"], 0), "sample_rate_hz"),
        (bad(["dips", 0, "depth"], 2), "dips[0].depth"),
        (bad(["dips", 0, "color"], [1, 2]), "dips[0].color"),
        (bad(["dips", 0, "before_sample"], delete=True), "dips[0].before_sample"),
        (bad(["seed"], -1), "seed"),
    ],
)
def test_bad_recordings_are_refused_naming_the_field(doc, field):
    with pytest.raises(RecordingError) as exc:
        from_dict(doc)
    assert field in str(exc.value)


def test_nan_in_json_text_is_refused():
    text = json.dumps(GOOD).replace("[10, 20, 34, 0, 0, 0]", "[10, 20, NaN, 0, 0, 0]")
    with pytest.raises(RecordingError, match=r"samples\[0\]\[2\]"):
        loads(text)
    with pytest.raises(RecordingError, match="not valid JSON"):
        loads("{")


def test_quality_params_are_validated():
    with pytest.raises(ParameterError, match="'tre'"):
        QualityParams(tre=-0.1)
    with pytest.raises(ParameterError, match="'dry'"):
        QualityParams(dry=float("nan"))
    assert len(QualityParams.names()) == 11


def test_every_shipped_preset_loads_and_is_in_range():
    for kind in ("brush", "paper", "ink"):
        names = preset_names(kind)
        assert len(names) >= 3, kind
        for n in names:
            p = load_preset(kind, n)
            for v in p.data.get("quality", {}).values():
                assert 0.0 <= v <= 1.0
    rec = from_dict(GOOD)
    for b in preset_names("brush"):
        rec.brush = {"preset": b}
        rec.resolve()
    from sim.fitting.search import load_quality

    for n in preset_names("quality"):  # fitted quality presets: all eleven values, in range
        q = load_quality(PRESET_DIR / "qualities" / f"{n}.json")
        assert len(q) == 11
        rec.quality = q
        rec.resolve()


def test_cli_render_and_clear_error(tmp_path):
    p = tmp_path / "r.json"
    p.write_text(json.dumps(GOOD))
    out = tmp_path / "o.png"
    r = subprocess.run(
        [sys.executable, "-m", "sim", "render", str(p), "-o", str(out), "-q"],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert r.returncode == 0, r.stderr
    from sim.image.png import read_png

    img = read_png(out)
    assert img.shape == (160, 240, 3)
    p.write_text(json.dumps(bad(["quality", "ab"], 3)))
    r = subprocess.run(
        [sys.executable, "-m", "sim", "render", str(p), "-o", str(out)],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert r.returncode == 2
    assert "quality.ab" in r.stderr and "Traceback" not in r.stderr


def test_the_papers_colour_and_capacity_travel_with_the_recording():
    import numpy as np

    from sim.core.recording import Recording, RecordingError, from_dict
    from sim.engine.simulation import Simulation

    samples = np.array([[20.0, 20.0, 40.0, 0, 0, 0], [20.0, 20.0, 24.0, 0, 0, 0]])
    rec = Recording(samples, width_mm=40, height_mm=40, px_per_mm=2.0)
    d = rec.to_dict()
    d["paper"].update(color=[0.9, 0.8, 0.6], capacity=0.25)
    back = from_dict(d)
    assert back.to_dict()["paper"]["color"] == [0.9, 0.8, 0.6]
    spec = back.resolve()[2]
    assert spec.color == (0.9, 0.8, 0.6) and spec.capacity == 0.25
    blank = Simulation(back).image()
    # the sheet's colour, with the default paper's texture about it (clouds and fibres, a few
    # per cent), and exactly it with the texture off
    assert np.allclose(blank.reshape(-1, 3).mean(axis=0), (0.9, 0.8, 0.6), rtol=0.02)
    assert 0.002 < blank[..., 0].std() < 0.03
    d["paper"]["texture"] = 0.0
    assert np.all(Simulation(from_dict(d)).image() == np.float32([0.9, 0.8, 0.6]))
    for bad, msg in (([1, 2], "must be"), ([0.5, 0.5, 2.0], "color"), ("x", "must be")):
        d["paper"]["color"] = bad
        with pytest.raises(RecordingError, match=msg):
            from_dict(d)
    d["paper"]["color"] = [1, 1, 1]
    d["paper"]["capacity"] = -1
    with pytest.raises(RecordingError, match="capacity"):
        from_dict(d)
    d["paper"]["capacity"] = 1.0
    for bad in (-0.1, 0.31, float("nan"), "x"):
        d["paper"]["texture"] = bad
        with pytest.raises(RecordingError, match="paper.texture"):
            from_dict(d)
