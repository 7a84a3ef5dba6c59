# SPDX-License-Identifier: GPL-3.0-or-later
"""``python -m sim fit``: the quality parameters fitted to training characters or images (Sec.
7.2, Eq. 28)."""

from __future__ import annotations

import argparse
import sys
import time

from ..core.params import ParameterError, short_repr
from .shared import _chars, _named, _progress, _response, _template, _whole, _writable


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
        samples = (
            character_samples(
                chars, args.size, template, names=args.chars, response=_response(template)
            )
            + samples
        )
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
    from ..fitting.samples import TRAINING_SIZE_PX
    from ..fitting.search import SETTING_RANGES, FitSettings

    f = sub.add_parser("fit", help="fit the quality parameters (Sec. 7.2, Eq. 28)")
    f.add_argument("--chars", nargs="*", default=[], help="training characters (stroke data)")
    f.add_argument("--image", nargs="*", help="training images (PNG) ...")
    f.add_argument("--image-recording", nargs="*", help="... and their recordings")
    f.add_argument("-o", "--output", type=_named, required=True, help="preset JSON to write")
    f.add_argument("--size", type=size, default=TRAINING_SIZE_PX, help="training image size")
    f.add_argument(
        "--seed-preset", type=_named, default=None, help="brush preset name or quality JSON"
    )
    defaults = FitSettings()  # the one home of the fit's defaults
    for name, help_ in (
        ("divisions", None),
        ("rounds", None),
        ("iterations", None),
        ("workers", "processes (0: all cores)"),
        ("max_grid", None),
    ):
        opt = "--" + name.replace("_", "-")
        kind = _whole(*SETTING_RANGES[name])
        f.add_argument(opt, type=kind, default=getattr(defaults, name), help=help_)
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
