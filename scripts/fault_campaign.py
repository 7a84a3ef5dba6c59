# SPDX-License-Identifier: GPL-3.0-or-later
"""Issue 30's fault campaign: generated bad inputs and injected faults, and what must hold.

    .venv/bin/python scripts/fault_campaign.py [--inputs 1000] [--faults 100] [--seed 0]

Bad inputs (seeded, generated here): recordings with every field in turn made hostile (NaN,
infinities, huge or wrong-typed values, missing or unknown fields), truncated, byte-flipped or
re-encoded; hostile option values and paths; damaged character files; damaged PNG pictures.
Each is given to ``python -m sim`` (in a worker process that runs the commands one after
another, restarted after a hang or a crash) with a good output file already in place.

Injected faults, each in its own child process or on its own copy: killed at the moment of
writing (SIGXFSZ at a random size), killed at a random moment (SIGKILL), a full disk (``ulimit
-f``), too little memory (``ulimit -v``), damaged farm caches, a farm cache save failing on a
random file, poisoned calibration caches.

What must hold, counted: no traceback, no hang, no file lost (every file there before is its
old self or a whole new file of its kind), no wrong image (a cache that loads gives exactly the
straight simulation). Temporary files a kill leaves are counted too (expected only after
kills). Prints a table and one JSON line of the figures."""

from __future__ import annotations

import argparse
import contextlib
import copy
import io
import json
import random
import selectors
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from tests.faults import (  # noqa: E402
    child_env,
    disk_full_at,
    leftovers,
    lost_files,
    run_sim,
    snapshot,
)

MB = 2**20
INPUT_SECONDS = 120.0  # a bad input's run longer than this is a hang
REC = {
    "format": "hairy-brush-recording",
    "version": 1,
    "paper": {
        "width_mm": 60,
        "height_mm": 40,
        "px_per_mm": 4,
        "preset": "raw_xuan",
        "color": [0.95, 0.93, 0.88],
        "capacity": 1.0,
        "fibre": 0.4,
    },
    "brush": {"preset": "wolf_kaishu", "geometry": {"hair_length_mm": 28.0}},
    "ink": {"preset": "sumi_black"},
    "quality": {"ren": 0.3, "ab": 0.5},
    "sample_rate_hz": 120,
    "seed": 3,
    "samples": [[10, 20, 34, 0, 0, 0], [12, 20, 24, 2, 1, 5], [30, 21, 24, 3, -2, 10]],
    "dips": [{"before_sample": 0, "depth": 0.8, "color": [0, 0, 0], "wetness": 0.9}],
}
HOSTILE = [
    float("nan"),
    float("inf"),
    float("-inf"),
    1e308,
    -1e308,
    10**400,
    -(10**30),
    2**64,
    -1,
    0,
    1e-320,
    "",
    "x",
    "NaN",
    None,
    True,
    [],
    {},
    [[1, 2]],
    "../../etc/passwd",
]
HOSTILE_TEXT = [
    "nan",
    "inf",
    "-inf",
    "1e400",
    "-1",
    "0",
    "",
    " ",
    "abc",
    "1e-400",
    "0x10",
    "18446744073709551616",
    "-0",
    "1_000",
    "9" * 5000,
    "\u00e9\u6c38",
]


@dataclass
class Tally:
    """Runs, and what went wrong, by kind."""

    runs: Counter = field(default_factory=Counter)
    tracebacks: list = field(default_factory=list)
    hangs: list = field(default_factory=list)
    lost: list = field(default_factory=list)
    wrong: list = field(default_factory=list)
    unexpected: list = field(default_factory=list)  # an exit code the fault should not give
    temporary: Counter = field(default_factory=Counter)
    outcomes: Counter = field(default_factory=Counter)

    def add(
        self,
        kind: str,
        what: str,
        *,
        traceback=False,
        hung=False,
        lost=(),
        wrong=False,
        unexpected=False,
    ):
        self.runs[kind] += 1
        if unexpected:
            self.unexpected.append(f"{kind}: {what}")
        if traceback:
            self.tracebacks.append(f"{kind}: {what}")
        if hung:
            self.hangs.append(f"{kind}: {what}")
        self.lost += [f"{kind}: {what}: {x}" for x in lost]
        if wrong:
            self.wrong.append(f"{kind}: {what}")


# ------------------------------------------------------------------------ bad inputs
def _leaves(node, path=()):
    if isinstance(node, dict):
        for k, v in node.items():
            yield from _leaves(v, (*path, k))
    elif isinstance(node, list) and node:
        for i, v in enumerate(node):
            yield from _leaves(v, (*path, i))
    yield path


def _set(doc, path, value):
    """doc[path] = value; nothing when an earlier change removed the path."""
    with contextlib.suppress(KeyError, IndexError, TypeError):
        node = doc
        for p in path[:-1]:
            node = node[p]
        node[path[-1]] = value


def _delete(doc, path):
    with contextlib.suppress(KeyError, IndexError, TypeError):
        node = doc
        for p in path[:-1]:
            node = node[p]
        del node[path[-1]]


def bad_recording(rng: random.Random) -> bytes:
    """A recording made hostile one way or another (as bytes of the file)."""
    doc = copy.deepcopy(REC)
    paths = [p for p in _leaves(doc) if p]
    way = rng.choice(["value", "value", "value", "delete", "extra", "text", "bytes", "shape"])
    if way == "value":
        for _ in range(rng.choice([1, 1, 2, 3])):
            _set(doc, rng.choice(paths), rng.choice(HOSTILE))
    elif way == "delete":
        _delete(doc, rng.choice(paths))
    elif way == "extra":
        node = doc if rng.random() < 0.5 else doc["paper"]
        node[rng.choice(["x", "paper", "samples", "__proto__", "brush"])] = rng.choice(HOSTILE)
    elif way == "shape":
        doc["samples"] = rng.choice(
            [
                [],
                [[1, 2, 3]],
                [[0] * 7],
                doc["samples"] * rng.choice([2, 20, 200]),
                [[rng.uniform(-1e4, 1e4) for _ in range(6)] for _ in range(rng.randint(1, 50))],
                "samples",
            ]
        )
    data = json.dumps(doc).encode("utf-8")  # NaN and Infinity written as JSON's extensions
    if way == "text":
        data = data[: rng.randrange(len(data))]
    elif way == "bytes":
        data = bytearray(data)
        for _ in range(rng.randint(1, 8)):
            data[rng.randrange(len(data))] = rng.randrange(256)
        data = bytes(data)
    if rng.random() < 0.03:
        data = rng.choice([b"", b"\xef\xbb\xbf" + data, json.dumps(doc).encode("utf-16")])
    return data


def bad_options(rng: random.Random, files: dict) -> list:
    """argv of a command given hostile option values or paths."""
    v = rng.choice(HOSTILE_TEXT)
    out = str(files["out"])
    paths = ["", " ", "/", "/proc/nope/x.png", str(files["dir"]), "no/such/dir/x.png", "x" * 300]
    bad_path = rng.choice(paths)
    char = str(files["char"])
    quick = ["--size", "32", "--passes", "1", "-q"]
    return rng.choice(
        [
            ["render", files["rec"], "--px-per-mm", v, "-o", out, "-q"],
            ["render", files["rec"], "--seed", v, "-o", out, "-q"],
            ["render", files["rec"], "-o", bad_path, "-q"],
            ["render", bad_path, "-o", out, "-q"],
            ["write", char, "--size", v, "-o", out, "-q"],
            ["write", char, "--size-mm", v, "-o", out, *quick],
            ["write", char, "--passes", v, "-o", out, "-q"],
            ["write", char, "--seed", v, "-o", out, *quick],
            ["write", char, rng.choice(["--brush", "--paper", "--ink"]), v, "-o", out, *quick],
            ["write", char, "--quality", rng.choice([bad_path, v]), "-o", out, *quick],
            ["write", char, "-o", bad_path, *quick],
            ["write", char, "--recording", bad_path, "-o", out, *quick],
            ["write", v or "x", "--data", rng.choice([bad_path, char]), "-o", out, *quick],
            ["write-set", char, "--out-dir", bad_path, *quick],
            ["write-set", char, "--workers", v, "--out-dir", files["dir"], *quick],
            ["imitate", rng.choice([bad_path, files["rec"], char]), "-o", out, "--size", "32"],
            ["iou", v or "x", "--size", v],
            ["fit", "-o", bad_path, "--chars", char, "--rounds", v],
        ]
    )


def bad_character(rng: random.Random, good: dict) -> bytes:
    """A character file (hanzi-writer JSON) damaged one way or another."""
    doc = copy.deepcopy(good)
    way = rng.choice(["value", "value", "delete", "shape", "bytes", "text"])
    paths = [p for p in _leaves(doc) if p]
    if way == "value":
        _set(doc, rng.choice(paths), rng.choice(HOSTILE + [1e6, -1e6, "M 0 0 Z"]))
    elif way == "delete":
        _delete(doc, rng.choice(paths))
    elif way == "shape":
        key = rng.choice(["strokes", "medians"])
        doc[key] = rng.choice([[], doc[key] * 40, [[]], [[[0, 0]]], "x", None])
    data = json.dumps(doc, ensure_ascii=False).encode("utf-8")
    if way == "bytes":
        data = bytearray(data)
        for _ in range(rng.randint(1, 6)):
            data[rng.randrange(len(data))] = rng.randrange(256)
        data = bytes(data)
    elif way == "text":
        data = data[: rng.randrange(len(data))]
    return data


def bad_png(rng: random.Random, good: bytes) -> bytes:
    """A PNG damaged in its header, chunks or data (the CRCs left as they were)."""
    data = bytearray(good)
    way = rng.choice(["flip", "truncate", "header", "chunk", "append"])
    if way == "flip":
        for _ in range(rng.randint(1, 4)):
            data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
    elif way == "truncate":
        data = data[: rng.randrange(len(data))]
    elif way == "header":
        data[16 + rng.randrange(13)] = rng.randrange(256)
    elif way == "chunk":
        data[33 + rng.randrange(4)] = rng.randrange(256)  # the first chunk's length
    else:
        data += bytes(rng.randrange(256) for _ in range(rng.randint(1, 64)))
    if bytes(data) == good:
        data = data[:-1]
    return bytes(data)


class Worker:
    """``python -m sim`` commands run one after another in one child (fast: no start-up each
    time); a command that takes too long or kills the child is reported and the child
    restarted."""

    def __init__(self, env):
        self.env, self.proc = env, None

    def _start(self):
        self.proc = subprocess.Popen(
            [sys.executable, __file__, "--worker"],
            cwd=ROOT,
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            text=True,
            env=self.env,
            preexec_fn=lambda: _limit_memory(2 << 30),
        )
        self.sel = selectors.DefaultSelector()
        self.sel.register(self.proc.stdout, selectors.EVENT_READ)

    def run(self, argv) -> dict:
        if self.proc is None or self.proc.poll() is not None:
            self._start()
        self.proc.stdin.write(json.dumps([str(a) for a in argv]) + "\n")
        self.proc.stdin.flush()
        if not self.sel.select(timeout=INPUT_SECONDS):
            self.stop()
            return {"code": None, "err": "", "hung": True}
        line = self.proc.stdout.readline()
        if not line:  # the child died
            code = self.proc.wait()
            self.proc = None
            return {"code": code, "err": f"worker died ({code})", "crashed": True}
        return json.loads(line)

    def stop(self):
        if self.proc is not None:
            self.proc.kill()
            self.proc.wait()
            self.proc = None


def _limit_memory(n: int):
    import resource

    resource.setrlimit(resource.RLIMIT_AS, (n, n))


def worker_loop():
    """--worker: run each argv line through the command line, one JSON result line each."""
    from sim.cli.main import main

    for line in sys.stdin:
        argv = json.loads(line)
        err, code, tb = io.StringIO(), None, False
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            try:
                code = main(argv)
            except SystemExit as exc:
                code = exc.code
            except BaseException:  # what the command line let escape: a traceback
                import traceback

                traceback.print_exc()
                tb = True
        text = err.getvalue()
        tb = tb or "Traceback (most recent call last)" in text
        print(json.dumps({"code": code, "err": text[-2000:], "traceback": tb}), flush=True)


def campaign_inputs(n: int, rng: random.Random, work: Path, tally: Tally, env) -> None:
    from sim.image.png import write_png

    files = {"dir": work / "out", "rec": work / "rec.json", "char": work / "char.json"}
    files["out"] = files["dir"] / "o.png"
    good_char = json.loads((ROOT / "data" / "hanzi" / "一.json").read_text(encoding="utf-8"))
    good_png = _picture(work)
    worker = Worker(env)
    mix = [("recording", 0.55), ("options", 0.25), ("character", 0.1), ("picture", 0.1)]
    try:
        for i in range(n):
            kind = rng.choices([k for k, _ in mix], [w for _, w in mix])[0]
            shutil.rmtree(files["dir"], ignore_errors=True)
            files["dir"].mkdir()
            write_png(files["out"], [[[0.5, 0.5, 0.5]]])  # the previous output, to keep
            files["rec"].write_text(json.dumps(REC))
            files["char"].write_text(json.dumps(good_char, ensure_ascii=False))
            if kind == "recording":
                files["rec"].write_bytes(bad_recording(rng))
                argv = ["render", files["rec"], "-o", files["out"], "-q"]
            elif kind == "options":
                argv = bad_options(rng, files)
            elif kind == "character":
                files["char"].write_bytes(bad_character(rng, good_char))
                argv = ["write", files["char"], "--size", "32", "--passes", "1", "-q"]
                argv += ["-o", files["out"]]
            else:
                pic = work / "pic.png"
                pic.write_bytes(bad_png(rng, good_png))
                argv = ["imitate", pic, "--size", "32", "--passes", "1", "-q", "-o", files["out"]]
            before = {"o.png": files["out"].read_bytes()}
            r = worker.run(argv)
            what = f"#{i} {' '.join(map(str, argv))[:160]}: {r.get('err', '')[-300:]}"
            tally.outcomes[f"exit {r.get('code')}"] += 1
            tally.add(
                f"input: {kind}",
                what,
                traceback=r.get("traceback", False) or r.get("crashed", False),
                hung=r.get("hung", False),
                lost=lost_files(before, files["dir"]),
                unexpected=r.get("code") not in (0, 2, 3) and not r.get("hung", False),
            )
            tally.temporary[f"input: {kind}"] += len(leftovers(files["dir"]))
            if (i + 1) % 100 == 0:
                print(f"{i + 1} bad inputs", file=sys.stderr, flush=True)
    finally:
        worker.stop()


def _picture(work: Path) -> bytes:
    """A small PNG of dark writing on a light ground, to damage."""
    import numpy as np

    from sim.image.png import write_png

    img = np.ones((48, 48, 3))
    img[20:28, 8:40] = 0.05
    write_png(work / "good.png", img)
    return (work / "good.png").read_bytes()


# ------------------------------------------------------------------------ faults
def campaign_faults(n: int, rng: random.Random, work: Path, tally: Tally, env) -> None:
    share = {
        "killed at write": 0.22,
        "killed at random": 0.16,
        "full disk": 0.16,
        "low memory": 0.2,
        "damaged farm cache": 0.14,
        "farm cache save fails": 0.08,
        "poisoned calibration": 0.04,
    }
    counts = {k: max(1, round(n * v)) for k, v in share.items()}
    rec = work / "rec.json"
    rec.write_text(json.dumps(REC))
    for k in range(counts["killed at write"]):
        _killed_at_write(rng, work / f"kw{k}", rec, tally, env)
    for k in range(counts["killed at random"]):
        _killed_at_random(rng, work / f"kr{k}", tally, env)
    for k in range(counts["full disk"]):
        _full_disk(rng, work / f"fd{k}", rec, tally, env)
    for k in range(counts["low memory"]):
        _low_memory(rng, work / f"lm{k}", tally, env)
    _farm_caches(rng, work / "farm", counts, tally)
    for k in range(counts["poisoned calibration"]):
        _poisoned_calibration(rng, work / f"pc{k}", k, tally, env)


def _outputs(folder: Path) -> Path:
    from sim.image.png import write_png

    folder.mkdir(parents=True, exist_ok=True)
    out = folder / "o.png"
    write_png(out, [[[0.5, 0.5, 0.5]]])
    (folder / "o.json").write_text(json.dumps(REC))
    return out


def _judge(kind, folder, argv, run, tally, ok_codes):
    before = getattr(run, "before", {})
    what = f"{' '.join(map(str, argv))[:160]}: {run.code} {run.message[:200]}"
    bad_code = run.code not in ok_codes and not run.hung
    tally.outcomes[f"{kind}: exit {run.code}"] += 1
    tally.add(
        kind,
        what,
        traceback=run.traceback,
        hung=run.hung or run.left_running,  # a process left running waits for ever
        lost=lost_files(before, folder),
        unexpected=bad_code,
    )
    tally.temporary[kind] += len(leftovers(folder))


def _killed_at_write(rng, folder, rec, tally, env):
    out = _outputs(folder)
    cmd = rng.choice(["render", "write-set", "write"])
    if cmd == "render":
        argv = ["render", rec, "-o", out, "-q"]
    elif cmd == "write":
        argv = ["write", "一", "--size", "64", "--passes", "1", "-q", "-o", out]
        argv += ["--recording", folder / "o.json"]
    else:
        argv = ["write-set", "一", "--size", "64", "--passes", "1", "--workers", "1", "-q"]
        argv += ["--out-dir", folder]
    before = snapshot(folder)
    run = run_sim(argv, file_size=rng.randrange(0, 6000), killed_at_write=True, env=env)
    run.before = before
    _judge("killed at write", folder, argv, run, tally, (0, -signal.SIGXFSZ))


def _killed_at_random(rng, folder, tally, env):
    out = _outputs(folder)
    argv = ["render", ROOT / "examples" / "strokes.json", "-o", out, "-q"]
    if rng.random() < 0.4:
        argv = ["write-set", "一", "十", "--size", "64", "--passes", "1", "--workers", "1"]
        argv += ["-q", "--out-dir", folder]
    before = snapshot(folder)
    run = run_sim(argv, kill_after=rng.uniform(0.2, 5.0), env=env)
    run.before = before
    _judge("killed at random", folder, argv, run, tally, (0, -signal.SIGKILL))


def _full_disk(rng, folder, rec, tally, env):
    out = _outputs(folder)
    argv = rng.choice(
        [
            ["render", rec, "-o", out, "-q"],
            [
                "write",
                "一",
                "--size",
                "64",
                "--passes",
                "1",
                "-q",
                "-o",
                out,
                "--recording",
                folder / "o.json",
            ],
            [
                "write-set",
                "一",
                "--size",
                "64",
                "--passes",
                "1",
                "--workers",
                "1",
                "-q",
                "--out-dir",
                folder,
            ],
        ]
    )
    before = snapshot(folder)
    run = run_sim(argv, file_size=rng.randrange(0, 6000), env=env)
    run.before = before
    ok = run.code == 0 or (run.code == 2 and "cannot write" in run.message)
    _judge("full disk", folder, argv, run, tally, (run.code,) if ok else ())


def _low_memory(rng, folder, tally, env):
    out = _outputs(folder)
    memory = rng.randrange(100, 320) * MB
    if rng.random() < 0.6:
        ppm = rng.choice(["4", "8", "16"])
        argv = ["render", ROOT / "examples" / "strokes.json", "--px-per-mm", ppm]
    else:
        argv = ["write", "一", "--size", rng.choice(["64", "256", "1024"]), "--passes", "1"]
    argv += ["-q", "-o", out]
    before = snapshot(folder)
    run = run_sim(argv, memory=memory, env=env, seconds=120)
    run.before = before
    said = run.code == 3 and "MB" in run.message
    _judge("low memory", folder, argv, run, tally, (0, 3) if run.code == 0 or said else ())


def _farm_caches(rng, folder, counts, tally):
    """Damaged caches load as CacheError or exactly; a failing save keeps the old cache."""
    import numpy as np

    from sim.core.recording import from_dict
    from sim.engine.checkpoints import (
        CacheError,
        cache_key_of,
        load_checkpoints,
        save_checkpoints,
    )
    from sim.engine.simulation import Simulation
    from sim.engine.timeline import Timeline

    def timeline(samples):
        return Timeline(Simulation(from_dict({**REC, "samples": samples, "dips": []})), every=2)

    a = [[10, 20, 34, 0, 0, 0]] + [[10 + 2 * i, 20, 24, 0, 0, 0] for i in range(20)]
    b = [[10, 30, 34, 0, 0, 0]] + [[10 + 2 * i, 30 - i / 2, 23, 0, 0, 0] for i in range(20)]
    straight = {t: timeline(a).seek(t).paper.ink.copy() for t in (5, 13, 20)}

    def bake(samples, where, key):
        tl = timeline(samples)
        tl.seek(len(samples))
        save_checkpoints(tl, where, key)

    bake(a, folder / "a", "A")
    bake(b, folder / "b", "B")

    def judge(kind, where, what, lost=(), must_load=False):
        """A cache loads exactly or is refused whole (CacheError); ``must_load``: it is A's
        own cache, which must still load."""
        fresh = timeline(a)
        try:
            load_checkpoints(fresh, where, "A")
        except CacheError:
            gone = ["A's cache no longer loads"] if must_load else []
            tally.add(kind, what, lost=[*lost, *gone], wrong=list(fresh.snaps) != [0])
            return
        except Exception as exc:  # noqa: BLE001 - anything but CacheError is a failure here
            tally.add(kind, f"{what}: {type(exc).__name__}: {exc}", traceback=True, lost=lost)
            return
        wrong = any(not np.array_equal(fresh.seek(t).paper.ink, ink) for t, ink in straight.items())
        tally.add(kind, what, lost=lost, wrong=wrong)

    for k in range(counts["damaged farm cache"]):
        where = folder / f"d{k}"
        shutil.copytree(folder / "a", where)
        what = _damage_cache(rng, where, folder / "b")
        judge("damaged farm cache", where, what)
    for k in range(counts["farm cache save fails"]):
        where = folder / f"s{k}"
        shutil.copytree(folder / "a", where)
        before = snapshot(where)
        victim = rng.choice(sorted(p.name for p in where.iterdir()))
        try:
            with disk_full_at(victim[:19]):
                bake(b, where, "B")
        except OSError:
            lost = [] if snapshot(where) == before else ["the cache changed"]
            lost += [p.name for p in folder.iterdir() if p.name.startswith(f".{where.name}.")]
            judge("farm cache save fails", where, f"failed at {victim}", lost, must_load=True)
        else:  # the name was not written (B's files are named alike): B's cache, whole
            lost = [] if cache_key_of(where) == "B" else ["B's bake is not the cache"]
            tally.add("farm cache save fails", f"{victim}: not failed", lost=lost)


def _damage_cache(rng, where: Path, other: Path) -> str:
    files = sorted(where.glob("checkpoint_*.npz"))
    victim = rng.choice(files)
    way = rng.choice(["truncate", "zero", "flip", "delete", "swap", "manifest", "key", "extra"])
    if way == "truncate":
        victim.write_bytes(victim.read_bytes()[: rng.randrange(victim.stat().st_size)])
    elif way == "zero":
        victim.write_bytes(b"\0" * victim.stat().st_size)
    elif way == "flip":
        data = bytearray(victim.read_bytes())
        data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
        victim.write_bytes(bytes(data))
    elif way == "delete":
        victim.unlink()
    elif way == "swap":
        victim.write_bytes((other / victim.name).read_bytes())
    elif way == "manifest":
        m = where / "manifest.json"
        m.write_bytes(m.read_bytes()[: rng.randrange(m.stat().st_size)])
    elif way == "key":
        m = json.loads((where / "manifest.json").read_text())
        m["key"] = "B"
        (where / "manifest.json").write_text(json.dumps(m))
    else:
        (where / "checkpoint_99999999.npz").write_bytes(b"PK junk")
    return f"{way} {victim.name}"


POISONS = [
    lambda g: {**g, "press": g["press"][:3]},
    lambda g: {**g, "v": "60"},
    lambda g: {**g, "width": [float("nan")] * len(g["width"])},
    lambda g: {"press": [], "width": [], "lag": [], "v": 60.0},
    lambda g: {**g, "lag": [10**400] * len(g["lag"])},
]


def _poisoned_calibration(rng, folder, k, tally, env):
    cache = folder / "cache"
    cache.mkdir(parents=True)
    for f in Path(env["HAIRY_BRUSH_CACHE"]).glob("response-*.json"):
        shutil.copy(f, cache)
    good = {f.name: json.loads(f.read_text()) for f in cache.glob("response-*.json")}
    for name, doc in good.items():
        (cache / name).write_text(json.dumps(POISONS[k % len(POISONS)](doc)))
    out = _outputs(folder)
    argv = ["write", "一", "--size", "64", "--passes", "1", "-q", "-o", out]
    run = run_sim(argv, env={**env, "HAIRY_BRUSH_CACHE": str(cache)}, seconds=300)
    run.before = {}
    healed = all(json.loads((cache / n).read_text()) == d for n, d in good.items())
    _judge("poisoned calibration", folder, argv, run, tally, (0,) if healed else ())


# ------------------------------------------------------------------------ report
def report(tally: Tally, seconds: float, n_inputs: int) -> dict:
    inputs = sum(v for k, v in tally.runs.items() if k.startswith("input"))
    faults = sum(v for k, v in tally.runs.items() if not k.startswith("input"))
    print(f"{'kind':28s} {'runs':>6s} {'tmp files':>9s}")
    for kind, n in sorted(tally.runs.items()):
        print(f"{kind:28s} {n:6d} {tally.temporary[kind]:9d}")
    print("outcomes:", dict(sorted(tally.outcomes.items())))
    for name in ("tracebacks", "hangs", "lost", "wrong", "unexpected"):
        for line in getattr(tally, name)[:10]:
            print(f"  {name}: {line}")
    figures = {
        "bad_inputs": inputs,
        "injected_faults": faults,
        "tracebacks": len(tally.tracebacks),
        "hangs": len(tally.hangs),
        "files_lost": len(tally.lost),
        "wrong_images": len(tally.wrong),
        "unexpected_exits": len(tally.unexpected),
        "temporary_files_left": sum(tally.temporary.values()),
        "seconds": round(seconds),
    }
    print(
        f"{inputs} bad inputs and {faults} injected faults: {figures['tracebacks']} tracebacks, "
        f"{figures['hangs']} hangs, {figures['files_lost']} files lost, "
        f"{figures['wrong_images']} wrong images, {figures['unexpected_exits']} unexpected exits "
        f"({figures['temporary_files_left']} temporary files left by kills), {seconds:.0f} s"
    )
    print(json.dumps(figures))
    return figures


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--inputs", type=int, default=1000)
    ap.add_argument("--faults", type=int, default=100)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        worker_loop()
        return 0
    rng = random.Random(args.seed)
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="hairy-brush-faults-") as tmp:
        work = Path(tmp)
        env = child_env(HAIRY_BRUSH_CACHE=work / "cache", PYTHONPATH=ROOT)
        # the calibration measured once, so that runs time the fault and not the measuring
        warm = run_sim(
            ["write", "一", "--size", "32", "--passes", "1", "-q", "-o", work / "warm.png"],
            env=env,
            seconds=300,
        )
        assert warm.code == 0, warm.err
        tally = Tally()
        campaign_inputs(args.inputs, rng, work, tally, env)
        campaign_faults(args.faults, rng, work, tally, env)
    figures = report(tally, time.perf_counter() - t0, args.inputs)
    bad = figures["tracebacks"] + figures["hangs"] + figures["files_lost"]
    return 1 if bad + figures["wrong_images"] + figures["unexpected_exits"] else 0


if __name__ == "__main__":
    sys.exit(main())
