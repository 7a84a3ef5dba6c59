# SPDX-License-Identifier: GPL-3.0-or-later
"""``python -m sim iou``: written characters evaluated against their font outlines (IoU, with
the round pen's and the true discs' baselines), by the realism measure (sim.fitting.realism,
beside the font's own: a flat font scores about 0) and, as a diagnostic, by the five texture
statistics of sim.fitting.texture."""

from __future__ import annotations

import os
import time

from .shared import _chars, _response, _template, sized


def cmd_iou(args) -> int:
    """IoU against the outline and the five texture statistics (sim.fitting.texture) per character,
    then their means and one JSON line."""
    import json

    import numpy as np

    from ..fitting.realism import realism
    from ..fitting.texture import TextureStats, score, texture_stats
    from ..writing.outline import baseline_masks, iou, rasterise
    from ..writing.writer import coverage_mask, write_character

    chars = _chars(args.chars, args.data)
    template = _template(args)
    rows, resp, per = [], _response(template), {}
    for spec, ch in zip(args.chars, chars, strict=True):
        t0 = time.perf_counter()
        font = rasterise(ch, args.size)
        base = baseline_masks(ch, args.size)
        tpl, used = sized(args, template, resp, ch)  # the brush for --size-mm
        rec, used, sim = write_character(
            ch, args.size, tpl, size_mm=args.size_mm, response=used, passes=args.passes
        )
        dt = time.perf_counter() - t0
        ink = coverage_mask(sim)
        tex = texture_stats(sim.image())
        real, flat = realism(sim.image()), realism(_font_image(ch, args.size))
        name = spec if len(spec) == 1 else os.path.basename(spec)
        rows.append(
            (name, iou(base["round_pen"], font), iou(base["true_discs"], font), iou(ink, font))
        )
        per[name] = {"iou": round(rows[-1][3], 4), "texture": _rounded(tex), "score": score(tex)}
        per[name]["score"] = round(per[name]["score"], 4)
        per[name]["seconds"] = round(dt, 2)
        per[name]["realism"] = real.as_dict()
        per[name]["realism_font"] = round(flat.score, 4)
        print(
            f"{name:<8} round pen {rows[-1][1]:.3f}  true discs {rows[-1][2]:.3f}  "
            f"brush {rows[-1][3]:.3f}  realism {real.score:.3f} (font {flat.score:.3f})  "
            f"{_tex_line(tex)}  score {score(tex):.2f}  {dt:.1f} s",
            flush=True,
        )
    mean = np.mean([r[1:] for r in rows], axis=0)
    mtex = TextureStats(*np.mean([list(v["texture"].values()) for v in per.values()], axis=0))
    mscore = float(np.mean([v["score"] for v in per.values()]))
    mreal = float(np.mean([v["realism"]["score"] for v in per.values()]))
    mflat = float(np.mean([v["realism_font"] for v in per.values()]))
    print(
        f"{'mean':<8} round pen {mean[0]:.3f}  true discs {mean[1]:.3f}  brush {mean[2]:.3f}  "
        f"realism {mreal:.3f} (font {mflat:.3f})  {_tex_line(mtex)}  score {mscore:.2f}"
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
                "mean_realism": round(mreal, 4),
                "mean_realism_font": round(mflat, 4),
                "mean_texture": _rounded(mtex),
                "mean_texture_score": round(mscore, 4),
                "per_char": {r[0]: round(r[3], 4) for r in rows},
                "per_char_detail": per,
            },
            ensure_ascii=False,
        )
    )
    return 0


def _font_image(char, n: int):
    """The font's character as ink on white, 2x supersampled (a font renderer's edges)."""
    import numpy as np

    from ..writing.outline import rasterise

    cover = rasterise(char, 2 * n).reshape(n, 2, n, 2).mean(axis=(1, 3))
    return np.repeat(1.0 - cover[..., None], 3, axis=2)


def _rounded(tex) -> dict:
    return {k: round(float(v), 4) for k, v in tex.as_dict().items()}


def _tex_line(tex) -> str:
    d = tex.as_dict()
    return (
        f"tone {d['ink_tone']:.3f} white {d['flying_white']:.3f} partial {d['partial_ink']:.3f} "
        f"ragged {d['ragged_edge']:.3f} width {d['width_variation']:.2f}"
    )
