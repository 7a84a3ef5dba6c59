# SPDX-License-Identifier: GPL-3.0-or-later
"""Fault injection (issue 30), shared by tests/sim/test_faults.py, tests/blender/test_faults.py
and scripts/fault_campaign.py: ``python -m sim`` in a child process under a memory limit
(``ulimit -v``), a file-size limit (``ulimit -f``, a full disk as the writer sees it), killed at
the moment it writes past a given size (SIGXFSZ with its default action, which Python ignores
unless told), or killed at any moment (SIGKILL); and what must hold afterwards: no traceback, no
hang, and every file that was there before still whole."""

from __future__ import annotations

import contextlib
import errno
import os
import resource
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from tests.paths import ROOT

# runs the command line with SIGXFSZ's default action (terminate) back: with a file-size limit,
# the kernel kills the process at the very write that passes the limit
KILLED_AT_WRITE = (
    "import signal, sys; signal.signal(signal.SIGXFSZ, signal.SIG_DFL); "
    "from sim.cli.main import main; sys.exit(main(sys.argv[1:]))"
)


@dataclass
class Run:
    """How a child ended: its exit code (negative: the signal that killed it), its stderr,
    its wall time, whether it had to be stopped for running too long, and whether processes it
    started were still running after it ended (a pool's workers left waiting for ever)."""

    code: int | None
    err: str
    seconds: float
    hung: bool = False
    left_running: bool = False

    @property
    def traceback(self) -> bool:
        return "Traceback (most recent call last)" in self.err

    @property
    def message(self) -> str:
        """The last line the command printed on stderr (its one error line, if any)."""
        lines = [ln for ln in self.err.replace("\r", "\n").splitlines() if ln.strip()]
        return lines[-1] if lines else ""


def limits(memory: int | None = None, file_size: int | None = None):
    """A preexec_fn setting ``ulimit -v`` (bytes of address space) and ``ulimit -f`` (bytes a
    file may grow to) in the child."""

    def apply():
        if memory is not None:
            resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
        if file_size is not None:
            resource.setrlimit(resource.RLIMIT_FSIZE, (file_size, file_size))

    return apply


def child_env(**extra) -> dict:
    env = {k: v for k, v in os.environ.items() if not k.startswith("PYTEST")}
    env.update({k: str(v) for k, v in extra.items()})
    return env


def run_sim(
    argv,
    *,
    seconds: float = 120.0,
    memory: int | None = None,
    file_size: int | None = None,
    killed_at_write: bool = False,
    kill_after: float | None = None,
    env: dict | None = None,
) -> Run:
    """``python -m sim argv`` in a child under the given limits. ``killed_at_write``: the child
    dies (SIGXFSZ) at the write that passes ``file_size``. ``kill_after``: SIGKILL to the child
    (not to processes it started) after that many seconds. A child still running after
    ``seconds`` is killed and counted as hung; its own process group is then checked for
    processes left running, and they are killed."""
    code = ["-c", KILLED_AT_WRITE] if killed_at_write else ["-m", "sim"]
    t0 = time.perf_counter()
    with tempfile.TemporaryFile() as err:
        p = subprocess.Popen(
            [sys.executable, *code, *map(str, argv)],
            cwd=ROOT,
            stdout=subprocess.DEVNULL,
            stderr=err,
            env=env or child_env(),
            preexec_fn=limits(memory, file_size),
            start_new_session=True,  # its own process group: what it leaves can be found
        )
        hung = False
        if kill_after is not None:
            try:
                p.wait(timeout=kill_after)
            except subprocess.TimeoutExpired:
                p.send_signal(signal.SIGKILL)
        try:
            p.wait(timeout=seconds)
        except subprocess.TimeoutExpired:
            hung = True
            p.kill()
            p.wait()
        left = _group_left(p.pid)
        err.seek(0)
        text = err.read().decode("utf-8", "replace")
    return Run(p.returncode, text, time.perf_counter() - t0, hung, left)


def group_members(pgid: int) -> list[int]:
    """The processes of the process group ``pgid`` (Linux: read from /proc)."""
    members = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        with contextlib.suppress(OSError, ValueError, IndexError):
            fields = stat.read_text().rsplit(")", 1)[1].split()
            if int(fields[2]) == pgid and fields[0] != "Z":  # state, ppid, pgrp
                members.append(int(stat.parent.name))
    return members


def _group_left(pgid: int, grace: float = 3.0) -> bool:
    """Whether processes of the group ``pgid`` are still there ``grace`` seconds after its
    leader ended; they are killed."""
    end = time.perf_counter() + grace
    while True:
        try:
            os.killpg(pgid, 0)
        except ProcessLookupError:
            return False
        except PermissionError:
            return False
        if time.perf_counter() > end:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(pgid, signal.SIGKILL)
            return True
        time.sleep(0.05)


_FULL = []  # name fragments whose opening for writing fails while a disk_full_at is active


def _full_disk_hook(event, args):
    """The audit event "open" is (path, mode, flags): mode for open(), None for os.open."""
    if event != "open" or not _FULL or not isinstance(args[0], (str, bytes, os.PathLike)):
        return
    path, mode, flags = args
    writing = any(c in mode for c in "wax+") if mode else bool(flags & (os.O_WRONLY | os.O_RDWR))
    if writing and any(fragment in os.path.basename(os.fsdecode(path)) for fragment in _FULL):
        raise OSError(errno.ENOSPC, "No space left on device", os.fsdecode(path))


@contextlib.contextmanager
def disk_full_at(fragment: str):
    """In this process, opening a file whose name holds ``fragment`` for writing fails as on a
    full disk (ENOSPC), however the code opens it (an audit hook sees every open)."""
    if not getattr(sys, "_hairy_brush_full_disk_hook", False):
        sys.addaudithook(_full_disk_hook)
        sys._hairy_brush_full_disk_hook = True
    _FULL.append(fragment)
    try:
        yield
    finally:
        _FULL.remove(fragment)


def snapshot(folder: Path) -> dict:
    """{name: bytes} of the files in ``folder`` (not recursive)."""
    return {p.name: p.read_bytes() for p in sorted(Path(folder).iterdir()) if p.is_file()}


def lost_files(before: dict, folder: Path) -> list[str]:
    """Files of ``before`` that are gone or are neither their old bytes nor a whole new file
    of their kind (a PNG read back by the engine's reader, a JSON document that parses)."""
    lost = []
    for name, data in before.items():
        p = Path(folder) / name
        if not p.is_file():
            lost.append(f"{name}: gone")
        elif p.read_bytes() != data and not whole(p):
            lost.append(f"{name}: damaged ({p.stat().st_size} bytes)")
    return lost


def whole(path: Path) -> bool:
    """Whether the file is a complete PNG or JSON document."""
    import json

    from sim.image.png import PNGError, read_png

    if path.suffix == ".png":
        try:
            read_png(path)
            return True
        except PNGError:
            return False
    try:
        json.loads(path.read_text(encoding="utf-8"))
        return True
    except (ValueError, UnicodeDecodeError):
        return False


def leftovers(folder: Path) -> list[str]:
    """Temporary files a write left (only a kill may leave one)."""
    return sorted(p.name for p in Path(folder).iterdir() if p.name.endswith(".tmp"))
