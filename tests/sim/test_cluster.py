# SPDX-License-Identifier: GPL-3.0-or-later
"""Sec. 7.2 on a Dask cluster (issue 18): the same fit, bit for bit, as on this machine's own
processes; a clear error when the scheduler cannot be reached."""

import pytest

pytest.importorskip("distributed")

from sim.core.params import QP2, ParameterError  # noqa: E402
from sim.fitting.search import FitSettings, fit  # noqa: E402
from tests.sim.test_imitate import _line_samples  # noqa: E402


@pytest.mark.slow
def test_a_fit_on_a_local_dask_cluster_equals_the_local_fit():
    known = {"e": 0.3, "ie": 0.6, **{k: 0.0 for k in QP2}}
    samples = _line_samples(known)
    seed = {"e": 0.7, "ie": 0.2, **{k: 0.0 for k in QP2}}
    common = dict(divisions=1, rounds=1, iterations=3, workers=2, stages=("qp1",))
    common["only"] = ("e", "ie")
    local = fit(samples, seed, FitSettings(**common))
    dask = fit(samples, seed, FitSettings(**common, scheduler="local"))
    assert dask.quality == local.quality
    assert dask.target == local.target and dask.evaluations == local.evaluations
    assert dask.history == local.history


@pytest.mark.slow
def test_an_unreachable_scheduler_is_one_clear_error(monkeypatch):
    import sim.fitting.cluster

    monkeypatch.setattr(sim.fitting.cluster, "CONNECT_TIMEOUT_S", 2)
    samples = _line_samples({"e": 0.3, **{k: 0.0 for k in QP2}}, n=1)
    settings = FitSettings(rounds=1, iterations=1, workers=1, scheduler="tcp://127.0.0.1:9")
    with pytest.raises(ParameterError, match="cannot reach the Dask scheduler"):
        fit(samples, None, settings)


@pytest.mark.slow
def test_the_batch_writer_gives_the_same_files_on_a_dask_cluster(tmp_path):
    from sim.cli.main import main

    outs = []
    for extra in ([], ["--scheduler", "local"]):
        out = tmp_path / ("dask" if extra else "local")
        out.mkdir()
        argv = ["write-set", "一", "十", "--out-dir", str(out), "--size", "64", "--passes", "1"]
        assert main([*argv, "--workers", "2", "-q", *extra]) == 0
        outs.append(out)
    names = sorted(p.name for p in outs[0].iterdir())
    assert names == ["000.json", "000.png", "001.json", "001.png"]
    for name in names:
        assert (outs[0] / name).read_bytes() == (outs[1] / name).read_bytes()
