# SPDX-License-Identifier: GPL-3.0-or-later
"""A recording's ink colour and dips that follow it (issue 29.1): old recordings load and
render as they did; a dip that follows the ink loads the recording's ink colour."""

from __future__ import annotations

import copy

import numpy as np
import pytest

from sim.core.recording import RecordingError, from_dict
from sim.engine.simulation import Simulation

STROKE = [[20.0, 20.0, 34.0, 0, 0, 0]] + [[20.0 + i, 20.0, 24.0, 0, 0, 0] for i in range(24)]
OLD = {  # a recording as written before dips could follow the ink
    "format": "hairy-brush-recording",
    "version": 1,
    "paper": {"width_mm": 60, "height_mm": 40, "px_per_mm": 3},
    "ink": {"preset": "sumi_black"},
    "sample_rate_hz": 120,
    "seed": 3,
    "samples": STROKE,
    "dips": [{"before_sample": 0, "depth": 0.8, "color": [0.1, 0.2, 0.7], "wetness": 0.9}],
}


def with_(**changes) -> dict:
    d = copy.deepcopy(OLD)
    for key, value in changes.items():
        d[key] = value
    return d


def test_an_old_recording_keeps_its_dips_colours_and_its_text():
    rec = from_dict(OLD)
    assert not rec.dips[0].follows_ink
    assert rec.to_dict()["dips"] == OLD["dips"]  # no new field written for it
    assert rec.resolve()[3].color != (0.1, 0.2, 0.7)
    assert rec.dips[0].color_with(rec.resolve()[3]) == (0.1, 0.2, 0.7)


def test_a_dip_that_follows_the_ink_loads_the_recordings_ink_colour():
    red = [0.8, 0.05, 0.05]
    follows = with_(
        ink={"preset": "sumi_black", "color": red},
        dips=[{**OLD["dips"][0], "follows_ink": True}],
    )
    rec = from_dict(follows)
    assert rec.dips[0].follows_ink and rec.resolve()[3].color == tuple(red)
    assert from_dict(rec.to_dict()).dips[0].follows_ink  # kept through save and load
    own_red = with_(dips=[{**OLD["dips"][0], "color": red}])
    a = Simulation(rec).run().paper.rgb()
    b = Simulation(from_dict(own_red)).run().paper.rgb()
    np.testing.assert_array_equal(a, b)  # the same as a dip recorded in that colour
    ink = a[a[..., 1] < 0.5]
    assert len(ink) > 20 and ink[:, 0].mean() > 0.6


def test_without_dips_the_default_dip_is_the_papers_black_whatever_the_ink():
    named = from_dict(with_(dips=[], ink={"preset": "sumi_black", "color": [0.8, 0.1, 0.1]}))
    (dip,) = named.dips_or_default()
    assert not dip.follows_ink and dip.color_with(named.resolve()[3]) == (0.0, 0.0, 0.0)


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"ink": {"color": [1, 0]}}, "'ink.color' must be [r, g, b]"),
        ({"ink": {"color": [1, 0, 2]}}, "'ink.color[2]' must lie in"),
        (
            {"dips": [{"before_sample": 0, "follows_ink": 1}]},
            "'dips[0].follows_ink' must be true or false",
        ),
    ],
)
def test_bad_ink_colours_and_flags_get_one_clear_message(changes, message):
    with pytest.raises(RecordingError) as exc:
        from_dict(with_(**changes))
    assert message in str(exc.value)
