# SPDX-License-Identifier: GPL-3.0-or-later
"""``python -m sim speed``: what users wait for, measured as they run it, beside the previous
version measured in the same run (a ratio survives a noisy machine).

Every figure is a command of the command line run in a child process, so the same measurement
runs on any version of the project, however its insides changed: ``--against REV`` checks out
REV (a git revision) in a temporary worktree, ``--baseline DIR`` uses a checkout that is
there. The two versions take turns, run after run; each figure is the median of the runs with
their range.

The figures (issue 28): CPU seconds to write a character the project has never seen at 512 px
with the defaults, the calibration cache warm; wall seconds for a 20-character work at 256 px
a character on this machine's cores (``compose`` where the version has it, else ``write-set``
of the same characters); samples a second of the engine at 1 primitive on 2048 px and 16
primitives on 4096 px (``bench --quick``); peak memory of rendering an A4 sheet at 600 dpi."""

from __future__ import annotations

import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
HELD_OUT = ("出", "左", "生")  # tests/data/unseen: never tuned on (one a run, in turn)
WORK_CHARS = 20
A4_MM = (210.0, 297.0)
A4_PX_PER_MM = 600 / 25.4
GOALS = {
    "write_cpu_s": "goal <= 3 s, moonshot 1 s",
    "work20_wall_s": "goal <= 60 s, moonshot 30 s",
    "samples_per_s_1p_2048": "goal 2,000",
    "samples_per_s_16p_4096": "goal 240",
    "a4_600dpi_peak_mb": "under 2,048 MB",
    "a4_600dpi_blender_peak_mb": "under 2,048 MB",
}
LABELS = {
    "write_cpu_s": "write a held-out character, 512 px (CPU s)",
    "work20_wall_s": f"{WORK_CHARS}-character work, 256 px a character (wall s)",
    "samples_per_s_1p_2048": "engine, 1 primitive on 2048 px (samples/s)",
    "samples_per_s_16p_4096": "engine, 16 primitives on 4096 px (samples/s)",
    "a4_600dpi_peak_mb": "render an A4 sheet at 600 dpi (peak MB)",
    "a4_600dpi_blender_peak_mb": "the same in Blender: import, simulate (peak MB)",
}
# the artist's path in Blender (the bpy module), run by this checkout's script on each version's
# add-on: an A4 recording imported at 600 dpi and simulated into the paper image; the engine
# (sim/) itself never imports bpy
BLENDER_A4 = ROOT / "scripts" / "blender_a4.py"


@dataclass
class Version:
    """A checkout of the project, with caches of its own (warm after its first run)."""

    name: str
    root: Path
    cache: Path
    runs: dict = field(default_factory=dict)  # figure -> [values]

    def env(self) -> dict:
        env = dict(os.environ)
        env["HAIRY_BRUSH_CACHE"] = str(self.cache)
        env["XDG_CACHE_HOME"] = str(self.cache)  # versions from before $HAIRY_BRUSH_CACHE
        env["PYTHONPATH"] = str(self.root)
        env["BLENDER_USER_RESOURCES"] = str(self.cache / "blender_user")  # not the user's own
        return env

    def has_command(self, name: str) -> bool:
        r = subprocess.run(
            [sys.executable, "-m", "sim", name, "--help"],
            cwd=self.root,
            env=self.env(),
            capture_output=True,
        )
        return r.returncode == 0


def measured(cmd: list, version: Version) -> tuple[float, float, float, str]:
    """(wall s, CPU s, peak MB, stdout) of one command run in the version's checkout."""
    t0 = time.perf_counter()
    with tempfile.TemporaryFile() as out:
        p = subprocess.Popen(
            cmd, cwd=version.root, env=version.env(), stdout=out, stderr=subprocess.DEVNULL
        )
        _pid, status, use = os.wait4(p.pid, 0)
        wall = time.perf_counter() - t0
        out.seek(0)
        text = out.read().decode("utf-8", "replace")
    if os.waitstatus_to_exitcode(status) != 0:
        raise RuntimeError(f"{' '.join(map(str, cmd))} failed in {version.root}")
    return wall, use.ru_utime + use.ru_stime, use.ru_maxrss / 1024.0, text


def _work_folder(tmp: Path) -> tuple[Path, list[str]]:
    """Stroke data of the work's characters, in one folder both versions can read."""
    folder = tmp / "work_chars"
    folder.mkdir()
    files = sorted((ROOT / "data" / "hanzi").glob("*.json"))
    files += sorted(f for f in (ROOT / "tests" / "data" / "unseen").glob("*.json"))
    chars = []
    for f in files[:WORK_CHARS]:
        shutil.copy(f, folder / f.name)
        chars.append(f.stem)
    return folder, chars


def _a4_recording(tmp: Path) -> Path:
    """The demo character's recording on an A4 sheet (it renders at any resolution)."""
    from ..core.recording import from_dict
    from ..writing.hanzi import character_recording

    d = character_recording(ROOT / "data" / "hanzi" / "永.json").to_dict()
    d["paper"]["width_mm"], d["paper"]["height_mm"] = A4_MM
    path = tmp / "a4.json"
    from_dict(d).save(path)
    return path


def run_once(version: Version, k: int, tmp: Path, work: tuple[Path, list[str]], a4: Path):
    """One run of every figure in one version."""
    py = [sys.executable, "-m", "sim"]
    out = tmp / f"{version.name}_{k}"
    out.mkdir()
    char = HELD_OUT[k % len(HELD_OUT)]
    unseen = str(ROOT / "tests" / "data" / "unseen")
    write = py + ["write", char, "--data", unseen, "--size", "512", "-q", "-o", str(out / "w.png")]
    if k == 0:
        measured(write, version)  # the calibration cache warmed (not counted)
    version.runs.setdefault("write_cpu_s", []).append(measured(write, version)[1])
    folder, chars = work
    if version.has_command("compose"):
        cmd = py + ["compose", "".join(chars), "--data", str(folder), "--char-size", "256"]
        cmd += ["-q", "-o", str(out / "work.png")]
    else:
        cmd = py + ["write-set", *chars, "--data", str(folder), "--size", "256", "--workers"]
        cmd += [str(os.cpu_count() or 1), "-q", "--out-dir", str(out)]
    version.runs.setdefault("work20_wall_s", []).append(measured(cmd, version)[0])
    bench = json.loads(measured(py + ["bench", "--quick"], version)[3].strip().splitlines()[-1])
    for key in ("samples_per_s_1p_2048", "samples_per_s_16p_4096"):
        version.runs.setdefault(key, []).append(float(bench[key]))
    render = py + ["render", str(a4), "--px-per-mm", f"{A4_PX_PER_MM:.6f}", "-q"]
    peak = measured(render + ["-o", str(out / "a4.png")], version)[2]
    version.runs.setdefault("a4_600dpi_peak_mb", []).append(peak)
    blender = [sys.executable, str(BLENDER_A4), str(version.root), str(a4), str(A4_PX_PER_MM)]
    peak = measured(blender, version)[2]
    version.runs.setdefault("a4_600dpi_blender_peak_mb", []).append(peak)


def _figure(values) -> str:
    med = statistics.median(values)
    return f"{med:9.2f} [{min(values):.2f}-{max(values):.2f}]"


def report(versions: list[Version]) -> dict:
    """The table (median [min-max] per version, and this version's over the baseline's) and
    one JSON line."""
    res = {}
    head = f"{'figure':<50} {'this version':>24}"
    if len(versions) > 1:
        head += f" {'previous version':>24} {'ratio':>7}"
    print(head)
    for key, label in LABELS.items():
        row = f"{label:<50} {_figure(versions[0].runs[key]):>24}"
        res[key] = {v.name: sorted(v.runs[key]) for v in versions}
        if len(versions) > 1:
            ratio = statistics.median(versions[0].runs[key]) / statistics.median(
                versions[1].runs[key]
            )
            row += f" {_figure(versions[1].runs[key]):>24} {ratio:7.2f}"
            res[key]["ratio"] = round(ratio, 3)
        print(f"{row}   {GOALS[key]}")
    cpu = os.cpu_count()
    print(f"machine: {cpu} cores; {len(versions[0].runs['write_cpu_s'])} runs a version")
    print(json.dumps(res))
    return res


def main(repeats: int, baseline: str | None = None, against: str | None = None) -> dict:
    with tempfile.TemporaryDirectory(prefix="hairy-brush-speed-") as t:
        tmp = Path(t)
        versions = [Version("this", ROOT, tmp / "cache_this")]
        made = None
        if against:
            made = tmp / "previous"
            subprocess.run(
                ["git", "-C", str(ROOT), "worktree", "add", "--detach", str(made), against],
                check=True,
                capture_output=True,
            )
            baseline = str(made)
        if baseline:
            versions.append(Version("previous", Path(baseline).resolve(), tmp / "cache_prev"))
        try:
            work, a4 = _work_folder(tmp), _a4_recording(tmp)
            for k in range(repeats):
                for v in versions if k % 2 == 0 else versions[::-1]:  # take turns
                    run_once(v, k, tmp, work, a4)
                    sys.stderr.write(f"run {k + 1}/{repeats}: {v.name} done\n")
            return report(versions)
        finally:
            if made is not None:
                subprocess.run(
                    ["git", "-C", str(ROOT), "worktree", "remove", "--force", str(made)],
                    capture_output=True,
                )
