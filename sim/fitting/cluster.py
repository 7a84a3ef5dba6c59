# SPDX-License-Identifier: GPL-3.0-or-later
"""Sec. 7.2's evaluations on a Dask distributed cluster (the command line only: Dask is an
optional dependency, never needed by the extension).

``DaskPool`` has the interface of the fit's local process pool (``map`` in order, ``close``):
the training samples are sent to the workers once, every task is evaluated there, and results
come back in the order of the tasks, so a fit gives the same result, bit for bit, on a cluster
as on one machine. ``scheduler`` is "local" (a LocalCluster on this machine, on loopback) or the
address of a running scheduler (``tcp://host:8786``)."""

from __future__ import annotations

from ..core.params import ParameterError

CONNECT_TIMEOUT_S = 10
PARENT_CHECK_S = 0.5  # how often a pool's worker looks whether its parent is still there


def exit_with_parent(parent: int) -> None:
    """A process pool's initializer: the worker ends once ``parent`` (the pid of the process
    that made the pool) is gone. A parent that is killed tells its pool nothing, and the
    workers would wait for tasks for ever (issue 30: a killed write-set left them running)."""
    import os
    import threading
    import time

    def watch():
        while os.getppid() == parent:
            time.sleep(PARENT_CHECK_S)
        os._exit(1)

    threading.Thread(target=watch, name="exit-with-parent", daemon=True).start()


def _run_with_samples(task, fn, samples, init):
    init(samples)  # the samples as the worker's own (what the local pool's initializer does)
    return fn(task)


def connect(scheduler: str, workers: int):
    """(client, cluster or None): a LocalCluster of ``workers`` processes on loopback for
    "local", else a client of the scheduler at that address."""
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise ParameterError("--scheduler needs Dask: pip install 'dask[distributed]'") from None
    cluster = None
    try:
        if scheduler == "local":
            cluster = LocalCluster(
                n_workers=max(workers, 1),
                threads_per_worker=1,
                host="127.0.0.1",
                dashboard_address=None,
            )
            return Client(cluster, timeout=CONNECT_TIMEOUT_S), cluster
        return Client(scheduler, timeout=CONNECT_TIMEOUT_S), None
    except (OSError, TimeoutError, ValueError) as exc:
        if cluster is not None:
            cluster.close()
        raise ParameterError(f"cannot reach the Dask scheduler at {scheduler}: {exc}") from None


def map_tasks(fn, tasks, workers: int, scheduler: str | None = None, done=None) -> list:
    """``[fn(t) for t in tasks]`` in this machine's processes, or on a Dask cluster when a
    scheduler is named; results in the tasks' order. ``done(k, total)`` after each result."""
    tasks = list(tasks)
    out = [None] * len(tasks)
    if scheduler is None:
        import os
        from concurrent.futures import ProcessPoolExecutor, as_completed

        pool = ProcessPoolExecutor(
            max(workers, 1), initializer=exit_with_parent, initargs=(os.getpid(),)
        )
        with pool as ex:
            futures = {ex.submit(fn, t): k for k, t in enumerate(tasks)}
            for n, fut in enumerate(as_completed(futures), 1):
                out[futures[fut]] = fut.result()
                if done is not None:
                    done(n, len(tasks))
        return out
    from distributed import as_completed as dask_completed

    client, cluster = connect(scheduler, workers)
    try:
        futures = client.map(fn, tasks, pure=False)
        index = {f.key: k for k, f in enumerate(futures)}
        for n, fut in enumerate(dask_completed(futures), 1):
            out[index[fut.key]] = fut.result()
            if done is not None:
                done(n, len(tasks))
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    return out


class DaskPool:
    def __init__(self, samples, scheduler: str, workers: int, init):
        self.client, self._cluster = connect(scheduler, workers)
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
        self.client.close()
        if self._cluster is not None:
            self._cluster.close()
