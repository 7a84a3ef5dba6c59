# SPDX-License-Identifier: GPL-3.0-or-later
"""A previous version of the project beside this one, for scripts that compare them
(``realism_rank.py``, ``readme_figures.py``): REV exported with ``git archive`` into a temporary
folder (no worktree left behind, whatever happens), and the command line of either version run
in a child process with its own cache folder, so that the same command runs on any version
however its insides changed (as ``python -m sim speed --against REV`` does)."""

from __future__ import annotations

import io
import os
import subprocess
import sys
import tarfile
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DEFAULT_AGAINST = "da71a3a"  # the version before issue 26's round of realism work


@dataclass(frozen=True)
class Version:
    """A checkout of the project and the cache folder its command line uses."""

    name: str
    root: Path
    cache: Path

    def sim(self, *args, check: bool = True) -> subprocess.CompletedProcess:
        """``python -m sim ARGS`` run in this version's checkout (stdout and stderr kept)."""
        env = dict(os.environ)
        env["HAIRY_BRUSH_CACHE"] = str(self.cache)
        env["XDG_CACHE_HOME"] = str(self.cache)  # versions from before $HAIRY_BRUSH_CACHE
        env["PYTHONPATH"] = str(self.root)
        r = subprocess.run(
            [sys.executable, "-m", "sim", *map(str, args)],
            cwd=self.root,
            env=env,
            capture_output=True,
            text=True,
        )
        if check and r.returncode != 0:
            raise RuntimeError(
                f"{self.name}: python -m sim {' '.join(map(str, args))} failed:\n{r.stderr[-2000:]}"
            )
        return r


def commit_of(rev: str) -> str:
    """REV's full commit hash (a clear error when git does not know it)."""
    r = subprocess.run(
        ["git", "-C", str(ROOT), "rev-parse", "--verify", f"{rev}^{{commit}}"],
        capture_output=True,
        text=True,
    )
    if r.returncode != 0:
        raise SystemExit(f"--against {rev}: not a revision of this repository")
    return r.stdout.strip()


@contextmanager
def versions(tmp: Path, against: str | None):
    """[this version, REV's] (only this one without REV); REV's files under tmp/previous."""
    this = Version("new", ROOT, tmp / "cache_new")
    if not against:
        yield [this]
        return
    commit = commit_of(against)
    data = subprocess.run(
        ["git", "-C", str(ROOT), "archive", "--format=tar", commit],
        check=True,
        capture_output=True,
    ).stdout
    folder = tmp / "previous"
    folder.mkdir()
    with tarfile.open(fileobj=io.BytesIO(data)) as tar:
        tar.extractall(folder, filter="data")
    yield [this, Version(f"old ({against})", folder, tmp / "cache_old")]
