# SPDX-License-Identifier: GPL-3.0-or-later
"""Sec. 7.2's evaluations on a Dask distributed cluster (the command line only: Dask is an
optional dependency, never needed by the extension).

``DaskPool`` has the interface of the fit's local process pool (``map`` in order, ``close``):
the training samples are sent to the workers once, every task is evaluated there, and results
come back in the order of the tasks, so a fit gives the same result, bit for bit, on a cluster
as on one machine. ``scheduler`` is "local" (a LocalCluster on this machine, on loopback) or the
address of a running scheduler (``tcp://host:8786``)."""

from __future__ import annotations

from .params import ParameterError

CONNECT_TIMEOUT_S = 10


def _run_with_samples(task, fn, samples, init):
    init(samples)  # the samples as the worker's own (what the local pool's initializer does)
    return fn(task)


class DaskPool:
    def __init__(self, samples, scheduler: str, workers: int, init):
        try:
            from distributed import Client, LocalCluster
        except ImportError:
            raise ParameterError(
                "--scheduler needs Dask: pip install 'dask[distributed]'"
            ) from None
        self._cluster = None
        try:
            if scheduler == "local":
                self._cluster = LocalCluster(
                    n_workers=max(workers, 1),
                    threads_per_worker=1,
                    host="127.0.0.1",
                    dashboard_address=None,
                )
                self.client = Client(self._cluster, timeout=CONNECT_TIMEOUT_S)
            else:
                self.client = Client(scheduler, timeout=CONNECT_TIMEOUT_S)
        except (OSError, TimeoutError, ValueError) as exc:
            self.close()
            raise ParameterError(f"cannot reach the Dask scheduler at {scheduler}: {exc}") from None
        self._samples = self.client.scatter(samples, broadcast=True)
        self._init = init
        init(samples)  # evaluations made here (the starting point) see them too

    def map(self, fn, tasks):
        futures = self.client.map(
            _run_with_samples,
            list(tasks),
            fn=fn,
            samples=self._samples,
            init=self._init,
            pure=False,
        )
        return self.client.gather(futures)

    def close(self):
        client = getattr(self, "client", None)
        if client is not None:
            client.close()
        if self._cluster is not None:
            self._cluster.close()
