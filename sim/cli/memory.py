# SPDX-License-Identifier: GPL-3.0-or-later
"""The command line within its memory (issue 30): when the memory runs out it says how much it
needed and exits (code 3), with no traceback and no hang.

Two things could go wrong besides numpy's own MemoryError. OpenBLAS, which numpy's matrix
products use, takes a workspace of about 32 MB on its first product and, when the system
refuses it (``ulimit -v``), retries for ever at 100% CPU. So the workspace is taken at start
(``reserve_workspace``: a probe says whether there is room, then one product takes it and every
later product reuses it), and the engine sets BLAS to one thread (``sim/__init__.py``), which
needs no second workspace and no thread structures allocated mid-product. And a paper too
large for the limit is refused before the long work (``check_room``)."""

from __future__ import annotations

import mmap

import numpy as np

EXIT_CODE = 3  # not enough memory (2: bad input)
WORKSPACE_BYTES = 48 * 2**20  # OpenBLAS's first product maps a 32 MB buffer; room to spare
# a render's memory a paper pixel: the paper (ink 12, wetness 4, last step 4), its RGB as floats
# (12) and as bytes (3), the PNG's filtered rows (about 4), rounded up; measured 35 B/px
RENDER_BYTES_PER_PIXEL = 40
ADVICE = "use a smaller image (--size; --px-per-mm for render) or allow the process more memory"


class NotEnoughMemory(Exception):
    """The command needs more memory than this process may have; the message says how much."""


def _mb(n: int) -> str:
    return f"{n / 2**20:.0f} MB"


def limit_bytes() -> int | None:
    """The address space this process may use (``ulimit -v``), None without a limit."""
    try:
        import resource
    except ImportError:  # not on this system
        return None
    soft = resource.getrlimit(resource.RLIMIT_AS)[0]
    return None if soft == resource.RLIM_INFINITY else int(soft)


def in_use_bytes() -> int | None:
    """The address space this process uses now (None where the system does not say)."""
    try:
        with open("/proc/self/status", encoding="ascii") as f:
            for line in f:
                if line.startswith("VmSize:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError):
        pass
    return None


def _limit_text(limit: int) -> str:
    used = in_use_bytes()
    now = f" and uses {_mb(used)}" if used is not None else ""
    return f"this process may use at most {_mb(limit)} (ulimit -v){now}"


def reserve_workspace() -> None:
    """Take BLAS's workspace now, or say how much memory starting needs."""
    limit = limit_bytes()
    if limit is not None:
        try:
            mmap.mmap(-1, WORKSPACE_BYTES).close()
        except (OSError, ValueError, MemoryError):
            used = in_use_bytes() or 0
            raise NotEnoughMemory(
                f"not enough memory to start: the engine needs about "
                f"{_mb(used + WORKSPACE_BYTES)}; {_limit_text(limit)}: allow it more memory"
            ) from None
    a = np.ones((256, 256))
    a @ a  # the workspace is mapped now, while there is room, and kept for every product


def check_room(need_bytes: int, what: str) -> None:
    """NotEnoughMemory, before the work, when ``what`` needs more than the limit leaves."""
    limit, used = limit_bytes(), in_use_bytes()
    if limit is not None and used is not None and used + need_bytes > limit:
        raise NotEnoughMemory(
            f"{what} needs about {_mb(need_bytes)} more memory; {_limit_text(limit)}: {ADVICE}"
        )


def out_of_memory(exc: MemoryError) -> str:
    """The message for a MemoryError: how much the failed allocation asked for, the limit."""
    size = getattr(exc, "_total_size", None)  # numpy's: the array it could not allocate
    asked = f" ({_mb(size)} more were needed at once)" if isinstance(size, int) else ""
    limit = limit_bytes()
    where = f"; {_limit_text(limit)}" if limit is not None else ""
    return f"not enough memory{asked}{where}: {ADVICE}"
