# SPDX-License-Identifier: GPL-3.0-or-later
"""Command line: ``python -m sim render REC.json -o OUT.png`` (from the repository root)."""

from __future__ import annotations

import argparse
import os
import sys
import time

from ..core.params import MAX_PAPER_SIDE_PX, ParameterError, number_within, short_repr
from ..core.recording import (
    DEFAULT_BRUSH,
    DEFAULT_PAPER,
    MAX_SEED,
    PAPER_MM_RANGE,
    PX_PER_MM_RANGE,
    RecordingError,
)


def _progress(frac: float) -> None:
    bar = int(frac * 30)
    sys.stderr.write(f"\r[{'#' * bar}{'.' * (30 - bar)}] {frac * 100:5.1f}%")
    if frac >= 1.0:
        sys.stderr.write("\n")
    sys.stderr.flush()


def _writable(path) -> None:
    """Refuse an output path whose folder does not exist before any long work."""
    folder = os.path.dirname(os.path.abspath(path))
    if os.path.isdir(path) or not os.path.isdir(folder):
        raise ParameterError(f"cannot write {path}: no such folder, or it is a folder")


def cmd_render(args) -> int:
    from ..core.recording import load
    from ..engine.simulation import Simulation
    from ..image.png import write_png

    _writable(args.output)
    rec = load(args.recording)
    if args.px_per_mm is not None:
        from ..core.recording import from_dict

        d = rec.to_dict()
        d["paper"]["px_per_mm"] = args.px_per_mm
        rec = from_dict(d)
    if args.seed is not None:
        rec.seed = args.seed
    t0 = time.perf_counter()
    sim = Simulation(rec).run(progress=None if args.quiet else _progress)
    write_png(args.output, sim.image8())
    if not args.quiet:
        dt = time.perf_counter() - t0
        print(
            f"{args.output}: {rec.width_px} x {rec.height_px} px, {len(rec.samples)} samples in "
            f"{dt:.2f} s, {sim.brush.m} writing primitive(s) at the end"
        )
    return 0


def _template(args):
    """A recording carrying the chosen brush, paper, ink, quality and seed (no samples yet)."""
    import numpy as np

    from ..core.recording import Recording

    quality = {}
    if getattr(args, "quality", None):
        from ..fitting.search import load_quality

        quality = load_quality(args.quality)
    rec = Recording(
        np.zeros((1, 6)),
        seed=args.seed,
        brush={"preset": args.brush},
        paper_preset=args.paper,
        ink={"preset": args.ink},
        quality=quality,
    )
    rec.resolve()  # the presets exist and are sound
    return rec


def _chars(specs, data):
    from ..writing.hanzi import find_char

    return [find_char(spec, data) for spec in specs]


def cmd_write(args) -> int:
    from ..image.png import write_png
    from ..writing.writer import write_character

    _writable(args.output)
    if args.recording:
        _writable(args.recording)
    (char,) = _chars([args.char], args.data)
    t0 = time.perf_counter()
    rec, resp, sim = write_character(
        char,
        args.size,
        _template(args),
        size_mm=args.size_mm,
        passes=args.passes,
        progress=None if args.quiet else _progress,
    )
    write_png(args.output, sim.image8())
    if args.recording:
        rec.save(args.recording)
    if not args.quiet:
        print(
            f"{args.output}: {args.size} x {args.size} px, {len(char['medians'])} strokes, "
            f"{len(rec.samples)} samples, {len(rec.dips)} dips, character {rec.width_mm:.1f} mm, "
            f"{time.perf_counter() - t0:.1f} s"
        )
    return 0


def _progress_after_reading(frac: float, *_details) -> None:
    """The bar from the first progress past reading the picture (a refused picture leaves
    only its error line)."""
    if frac > 0.0:
        _progress(frac)


def cmd_imitate(args) -> int:
    """Read a picture of writing, write it with the brush, report how close the ink is."""
    import json

    from ..fitting.texture import score, texture_stats
    from ..image.png import write_png
    from ..picture.imitate import imitate, ink_on
    from ..writing.outline import iou
    from ..writing.writer import coverage_mask

    for path in (args.output, args.recording, args.char_data):
        if path:
            _writable(path)
    t0 = time.perf_counter()
    rec, _, sim, im = imitate(
        args.image,
        _template(args),
        n_px=args.size,
        size_mm=args.size_mm,
        passes=args.passes,
        progress=None if args.quiet else _progress_after_reading,
        piece=args.piece,
    )
    write_png(args.output, sim.image8())
    if args.recording:
        rec.save(args.recording)
    if args.char_data:
        with open(args.char_data, "w", encoding="utf-8") as f:
            json.dump(im.char, f, separators=(",", ":"))
    if not args.quiet:
        ink = ink_on(im.ink.mask, args.size)  # read at most MAX_DETAIL a side
        print(
            f"{args.output}: {len(im.strokes)} strokes read in {im.seconds:.1f} s, "
            f"{len(rec.samples)} samples, character {rec.width_mm:.1f} mm, IoU with the "
            f"picture's ink {iou(coverage_mask(sim), ink):.3f}, texture score "
            f"{score(texture_stats(sim.image())):.2f}, {time.perf_counter() - t0:.1f} s"
        )
    return 0


def cmd_write_set(args) -> int:
    """Many characters to a folder of PNGs and recordings, on this machine's processes or a
    Dask cluster (the executor of ``fit --scheduler``)."""
    import json

    from ..fitting.cluster import map_tasks, write_task
    from ..image.png import write_png

    if not os.path.isdir(args.out_dir):
        raise ParameterError(f"--out-dir {args.out_dir}: no such folder")
    chars = _chars(args.chars, args.data)
    template = _template(args)
    tasks = [(c, f"{k:03d}", args.size, template, args.passes) for k, c in enumerate(chars)]
    t0 = time.perf_counter()
    workers = args.workers or os.cpu_count() or 1
    done = None if args.quiet else (lambda n, total: _progress(n / total))
    for name, rgb, rec in map_tasks(write_task, tasks, workers, args.scheduler, done):
        write_png(os.path.join(args.out_dir, name + ".png"), rgb)
        with open(os.path.join(args.out_dir, name + ".json"), "w", encoding="utf-8") as f:
            json.dump(rec, f, separators=(",", ":"))
    print(f"{args.out_dir}: {len(tasks)} characters, {time.perf_counter() - t0:.1f} s")
    return 0


def cmd_iou(args) -> int:
    """IoU against the outline and the five texture statistics (sim.fitting.texture) per character,
    then their means and one JSON line."""
    import json

    import numpy as np

    from ..fitting.texture import TextureStats, score, texture_stats
    from ..writing.outline import baseline_masks, iou, rasterise
    from ..writing.writer import coverage_mask, write_character

    chars = _chars(args.chars, args.data)
    template = _template(args)
    rows, resp, per = [], None, {}
    for spec, ch in zip(args.chars, chars, strict=True):
        t0 = time.perf_counter()
        font = rasterise(ch, args.size)
        base = baseline_masks(ch, args.size)
        rec, resp, sim = write_character(
            ch, args.size, template, size_mm=args.size_mm, response=resp, passes=args.passes
        )
        dt = time.perf_counter() - t0
        ink = coverage_mask(sim)
        tex = texture_stats(sim.image())
        name = spec if len(spec) == 1 else os.path.basename(spec)
        rows.append(
            (name, iou(base["round_pen"], font), iou(base["true_discs"], font), iou(ink, font))
        )
        per[name] = {"iou": round(rows[-1][3], 4), "texture": _rounded(tex), "score": score(tex)}
        per[name]["score"] = round(per[name]["score"], 4)
        per[name]["seconds"] = round(dt, 2)
        print(
            f"{name:<8} round pen {rows[-1][1]:.3f}  true discs {rows[-1][2]:.3f}  "
            f"brush {rows[-1][3]:.3f}  {_tex_line(tex)}  score {score(tex):.2f}  {dt:.1f} s",
            flush=True,
        )
    mean = np.mean([r[1:] for r in rows], axis=0)
    mtex = TextureStats(*np.mean([list(v["texture"].values()) for v in per.values()], axis=0))
    mscore = float(np.mean([v["score"] for v in per.values()]))
    print(
        f"{'mean':<8} round pen {mean[0]:.3f}  true discs {mean[1]:.3f}  brush {mean[2]:.3f}  "
        f"{_tex_line(mtex)}  score {mscore:.2f}"
    )
    print(
        json.dumps(
            {
                "size": args.size,
                "brush": args.brush,
                "paper": args.paper,
                "quality_file": args.quality,
                "passes": args.passes,
                "mean_iou_brush": round(float(mean[2]), 4),
                "mean_iou_round_pen": round(float(mean[0]), 4),
                "mean_iou_true_discs": round(float(mean[1]), 4),
                "mean_texture": _rounded(mtex),
                "mean_texture_score": round(mscore, 4),
                "per_char": {r[0]: round(r[3], 4) for r in rows},
                "per_char_detail": per,
            },
            ensure_ascii=False,
        )
    )
    return 0


def _rounded(tex) -> dict:
    return {k: round(float(v), 4) for k, v in tex.as_dict().items()}


def _tex_line(tex) -> str:
    d = tex.as_dict()
    return (
        f"tone {d['ink_tone']:.3f} white {d['flying_white']:.3f} partial {d['partial_ink']:.3f} "
        f"ragged {d['ragged_edge']:.3f} width {d['width_variation']:.2f}"
    )


def cmd_fit(args) -> int:
    from ..core.params import load_preset, quality_from_presets
    from ..core.recording import load
    from ..fitting.samples import character_samples, image_sample
    from ..fitting.search import FitSettings, fit, load_quality, save_preset

    _writable(args.output)
    if len(args.image or []) != len(args.image_recording or []):
        raise ParameterError("every --image needs its --image-recording")
    if not args.chars and not args.image:
        raise ParameterError("give training characters (--chars) or --image/--image-recording")
    template = _template(args)
    # the seed: a quality file, a brush preset's values, or (none given) the values the training
    # recordings already use - the chosen brush and paper presets and --quality
    seed_q = None
    if args.seed_preset:
        seed_q = (
            load_quality(args.seed_preset)
            if args.seed_preset.endswith(".json")
            else quality_from_presets(load_preset("brush", args.seed_preset), None)
        )
    settings = FitSettings(
        divisions=args.divisions,
        rounds=args.rounds,
        iterations=args.iterations,
        workers=args.workers,
        max_grid=args.max_grid,
        stages=args.stages,
        bounds=dict(args.bound),
        seed=args.seed,
        scheduler=args.scheduler,
    )
    chars = _chars(args.chars, args.data)
    image_recs = [load(rec) for rec in args.image_recording or []]
    if not args.quiet:
        sys.stderr.write("writing the training samples...\n")
    samples = [
        image_sample(rec, png) for png, rec in zip(args.image or [], image_recs, strict=True)
    ]
    if chars:
        samples = character_samples(chars, args.size, template, names=args.chars) + samples
    t0 = time.perf_counter()

    def progress(frac, stage, rnd, best):
        if not args.quiet:
            _progress(frac)
            sys.stderr.write(f"  {stage} round {rnd}: Eq. 28 = {best:.5f}\n")

    res = fit(samples, seed_q, settings, progress=progress)
    save_preset(res, args.output)
    print(
        f"{args.output}: Eq. 28 (mean per pixel) {res.start_target:.5f} -> {res.target:.5f}, "
        f"{res.evaluations} evaluations, {time.perf_counter() - t0:.0f} s"
    )
    print("  " + "  ".join(f"{k}={v:.3f}" for k, v in res.quality.items()))
    return 0


def cmd_bench(args) -> int:
    from .bench import main as bench

    bench(quick=args.quick)
    return 0


def _whole(lo: int, hi: int):
    """An argparse type: a whole number in [lo, hi]."""

    def parse(text: str) -> int:
        try:
            v = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"must be a whole number, got {short_repr(text)}"
            ) from None
        if not lo <= v <= hi:
            raise argparse.ArgumentTypeError(f"must lie in [{lo}, {hi}], got {short_repr(v)}")
        return v

    return parse


def _real(lo: float, hi: float):
    """An argparse type: a finite number in [lo, hi]."""

    def parse(text: str) -> float:
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"must be a number, got {short_repr(text)}") from None
        if not number_within(v, lo, hi):
            raise argparse.ArgumentTypeError(f"must lie in [{lo:g}, {hi:g}], got {text}")
        return v

    return parse


def _stages(text: str) -> tuple:
    stages = tuple(s.strip() for s in text.split(","))
    if not all(s in ("qp1", "qp2") for s in stages):
        raise argparse.ArgumentTypeError(f"must be qp1, qp2 or qp1,qp2, got {short_repr(text)}")
    return stages


def _bound(text: str) -> tuple:
    name, _, rest = text.partition("=")
    try:
        lo, hi = (float(v) for v in rest.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be NAME=LO,HI, got {short_repr(text)}") from None
    return name.strip(), (lo, hi)


def _add_fit(sub, size, common):
    """The ``fit`` command's options."""
    from ..fitting.search import SETTING_RANGES

    f = sub.add_parser("fit", help="fit the quality parameters (Sec. 7.2, Eq. 28)")
    f.add_argument("--chars", nargs="*", default=[], help="training characters (stroke data)")
    f.add_argument("--image", nargs="*", help="training images (PNG) ...")
    f.add_argument("--image-recording", nargs="*", help="... and their recordings")
    f.add_argument("-o", "--output", required=True, help="preset JSON to write")
    f.add_argument("--size", type=size, default=96, help="training image size")
    f.add_argument("--seed-preset", default=None, help="brush preset name or quality JSON")
    for name, default, help_ in (
        ("divisions", 1, None),
        ("rounds", 2, None),
        ("iterations", 6, None),
        ("workers", 0, "processes (0: all cores)"),
        ("max_grid", 64, None),
    ):
        opt = "--" + name.replace("_", "-")
        f.add_argument(opt, type=_whole(*SETTING_RANGES[name]), default=default, help=help_)
    f.add_argument("--stages", type=_stages, default=("qp1", "qp2"))
    f.add_argument(
        "--bound",
        type=_bound,
        action="append",
        default=[],
        metavar="NAME=LO,HI",
        help="a quality parameter's search interval, e.g. e=0,0.97 (repeatable)",
    )
    f.add_argument(
        "--scheduler",
        default=None,
        help="evaluate on a Dask cluster: 'local' (a LocalCluster here) or a scheduler's "
        "address (tcp://host:8786); needs pip install 'dask[distributed]'",
    )
    f.add_argument("-q", "--quiet", action="store_true")
    common(f)
    f.set_defaults(func=cmd_fit)


def _add_imitate(sub, size, common):
    """The ``imitate`` command's options."""
    from ..picture.imitate import MAX_DETAIL, PASSES

    im = sub.add_parser("imitate", help="read a picture of writing and write it with the brush")
    im.add_argument("image", help="dark writing on a light ground: PNG (JPEG etc. with Pillow)")
    im.add_argument("-o", "--output", required=True)
    im.add_argument(
        "--size",
        type=size,
        default=512,
        help=f"image size N (the em box) written; the picture is read at N, at most {MAX_DETAIL}",
    )
    im.add_argument("--recording", default=None, help="also save the recording it made")
    im.add_argument("--char-data", default=None, help="also save the strokes read (JSON)")
    im.add_argument(
        "--piece",
        action="store_true",
        help="a piece of several characters: columns right to left, each top to bottom, each "
        "character written in its own square of the sheet",
    )
    im.add_argument("-q", "--quiet", action="store_true")
    common(im)
    im.set_defaults(func=cmd_imitate, passes=PASSES)


def _parser() -> argparse.ArgumentParser:
    from ..writing.writer import DEFAULT_PASSES, MAX_PASSES, MIN_SHEET_PX

    seed = _whole(0, MAX_SEED)
    size = _whole(MIN_SHEET_PX, MAX_PAPER_SIDE_PX)
    ap = argparse.ArgumentParser(prog="python -m sim", description="Virtual Hairy Brush engine")
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("render", help="render a recording to a PNG")
    r.add_argument("recording")
    r.add_argument("-o", "--output", required=True)
    r.add_argument(
        "--px-per-mm", type=_real(*PX_PER_MM_RANGE), default=None, help="override the resolution"
    )
    r.add_argument("--seed", type=seed, default=None, help="override the seed")
    r.add_argument("-q", "--quiet", action="store_true")
    r.set_defaults(func=cmd_render)

    def common(p):
        p.add_argument("--data", default=None, help="folder of <char>.json or graphics.txt")
        p.add_argument("--brush", default=DEFAULT_BRUSH, help="brush preset")
        p.add_argument("--paper", default=DEFAULT_PAPER, help="paper preset")
        p.add_argument("--ink", default="sumi_black", help="ink preset")
        p.add_argument("--quality", default=None, help="quality JSON (e.g. from sim fit)")
        p.add_argument("--seed", type=seed, default=0)
        p.add_argument(
            "--size-mm", type=_real(*PAPER_MM_RANGE), default=None, help="character size (auto)"
        )
        p.add_argument(
            "--passes",
            type=_whole(1, MAX_PASSES),
            default=DEFAULT_PASSES,
            help="practice passes per stroke",
        )

    w = sub.add_parser("write", help="write a character from stroke data with the brush")
    w.add_argument("char", help="hanzi-writer JSON file, or one character (with --data)")
    w.add_argument("-o", "--output", required=True)
    w.add_argument("--size", type=size, default=512, help="image size N (the em box)")
    w.add_argument("--recording", default=None, help="also save the recording it made")
    w.add_argument("-q", "--quiet", action="store_true")
    common(w)
    w.set_defaults(func=cmd_write)
    _add_imitate(sub, size, common)
    ws = sub.add_parser("write-set", help="write many characters to a folder (PNG + recording)")
    ws.add_argument("chars", nargs="+", help="hanzi-writer JSON files, or characters")
    ws.add_argument("--out-dir", required=True, help="folder for NNN.png and NNN.json")
    ws.add_argument("--size", type=size, default=512, help="image size N (the em box)")
    ws.add_argument("--workers", type=_whole(0, 256), default=0, help="processes (0: all)")
    ws.add_argument("--scheduler", default=None, help="a Dask cluster, as for fit")
    ws.add_argument("-q", "--quiet", action="store_true")
    common(ws)
    ws.set_defaults(func=cmd_write_set)
    m = sub.add_parser("iou", help="IoU of written characters against the font outlines")
    m.add_argument("chars", nargs="+")
    m.add_argument("--size", type=size, default=512)
    common(m)
    m.set_defaults(func=cmd_iou)
    _add_fit(sub, size, common)
    b = sub.add_parser("bench", help="speed benchmark: a table, then one JSON line")
    b.add_argument("--quick", action="store_true", help="one repetition instead of three")
    b.set_defaults(func=cmd_bench)
    return ap


def main(argv=None) -> int:
    """Run a command; any bad input ends in one 'error:' line and exit code 2."""
    args = _parser().parse_args(argv)
    try:
        return args.func(args)
    except (RecordingError, ParameterError, ValueError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
