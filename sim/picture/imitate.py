# SPDX-License-Identifier: GPL-3.0-or-later
"""Imitating a picture (Sec. 9, "automatic imitation"): from a picture of writing to a
recording of the brush writing it.

1. The ink (``ink``): the picture fitted into the em box (small writing framed), the
   paper's uneven level divided out, a red seal taken for paper, Otsu's threshold, specks and
   pin-holes cleaned.
2. The strokes (``strokes``): the ink's skeleton as chains between junctions, spurs
   pruned, chains that continue each other by direction joined across junctions; each with its
   half-width along it (the distance transform).
3. Direction and order (``order``), as calligraphy is taught: a stroke runs left to right when it
   lies flat, else top to bottom, except that a stroke that rises to the right starts at its
   thicker end (where the brush entered: a rising 提 or a flat 撇, whose tail is a point);
   side-by-side parts of the character go left to right, and in each the strokes top to
   bottom, left to right, a horizontal before the stroke that crosses it or hangs from it, and
   after one that stands on it.
4. Character data (``outline``): each stroke's median, and as its outline the picture's own
   ink round it (the ink within its width of its median, the rest of the ink to the nearest
   stroke), traced into polygons; so ``writing.writer.write_character`` presses as wide as the
   picture's strokes and practises each stroke against the picture's ink.
5. Where the writing's shape agrees less than CORRECT_BELOW with the picture's (``corrections``
   times at most, see CORRECTIONS) the best writing so far read again against the picture's
   (``correct``): stroke ends that overshoot or fall short moved (from the second correction
   on, also the ends, corners and heads that set the box's sides), the character written
   again (not where it was written already), the best writing kept.

A piece of several characters is read a character at a time (``piece``). Everything here is
numpy only (it runs in Blender)."""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from .correct import corrected, shape_agreement
from .ink import Ink, PictureError, find_ink, grey_of, load_picture
from .outline import read_strokes
from .piece import read_piece

CORRECTIONS = 2  # the character written again at most this many times with its ends corrected,
# each time only while its shape agrees with the picture's less than CORRECT_BELOW, each time
# from the best writing so far; the best writing stays (``shape_agreement``). Off (0) it was: a
# scan of heavy kaishu's thin 横 tip or dot head written short moves the box, and every stroke
# against it. With one (and the heavy dot's reading, ``strokes._blob_stroke``): scans of heavy
# kaishu, 25 characters of two copybook pages never looked at (scripts/imitate_scans.py) box IoU
# 0.764 -> 0.791; Kaiti pictures made scan- and photo-like (scripts/imitate_eval.py) 0.845 ->
# 0.852, lowest 0.72 -> 0.81, no case lower; twice the time where it acts. The second also moves
# the ends that set the box's sides where the picture's lie (``correct.box_moves``): the 35
# crops of seven copybook pages 0.784 -> 0.795 (one case 0.015 lower), 19 crops of seven
# others 0.7998 -> 0.801 (時 in its grid 0.56 -> 0.48); three times the time where both act;
# and where no end points out of a side, the median's corner or end that sets it shifted
# across (``correct.box_shifts``: a hook's heel, a heavy head): 35 crops 0.795 -> 0.803, 19
# 0.801 -> 0.803. A correction that would write what was written already is not written.
CORRECT_BELOW = 0.85  # a writing whose shape agrees this well (the moonshot) is kept as it is
PASSES = 5  # practice passes per stroke: the picture's ink is the target (3: IoU 0.01 lower)
MAX_DETAIL = 2048  # px a side: a picture is read at most this fine (Blender's Detail, the CLI)


@dataclass
class Imitation:
    """What was read off a picture: its ink, the strokes in writing order (each running the
    way it is written), each stroke's own ink, the character data for the writer, and the
    seconds the reading took."""

    ink: Ink
    strokes: list
    regions: list
    char: dict
    seconds: float


def read_picture(source, n: int = 512, name: str | None = None, piece: bool = False) -> Imitation:
    """Read a picture (a PNG path, or an image array (H, W[, C])) into an Imitation on an
    n x n em box (n at most MAX_DETAIL); with ``piece``, a picture of several characters in
    columns is read as such (``read_piece``: each character in its own square). PictureError
    (or PNGError) for a picture this cannot imitate."""
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 0 < n <= MAX_DETAIL:
        raise PictureError(f"a picture is read at 1 to {MAX_DETAIL} px a side, got {n!r}")
    t0 = time.perf_counter()
    if isinstance(source, (str, bytes)) or hasattr(source, "__fspath__"):
        grey = load_picture(source)
        name = name or str(source)
    else:
        grey = grey_of(source, name or "the picture")
    ink = find_ink(grey, n, name or "the picture")
    found = read_piece(ink) if piece else None
    strokes, regions, char = found if found is not None else read_strokes(ink)
    if found is not None:  # the sheet's ink: each character in its square
        from ..writing.outline import rasterise

        sheet = rasterise(char, n)
        ink = Ink(sheet, sheet.astype(np.float64), 0.5, ink.separation)
    return Imitation(ink, strokes, regions, char, time.perf_counter() - t0)


def imitate(
    source,
    template,
    n_px: int = 512,
    progress=None,
    piece: bool = False,
    fit_brush: bool = True,
    cache_dir=None,
    **how,
):
    """Read a picture and write it with the brush (``write_imitation``, whose keywords ``how``
    passes on: size_mm, passes, px_per_mm, response, corrections) on an n_px sheet; the picture
    is read on an em box of n_px, at most MAX_DETAIL, px a side (the Imitation's ink is at that
    size). A character at a size_mm other than the brush's own for the strokes as read is
    written with the brush made smaller or larger for it (``writing.brush_size``; not with
    ``fit_brush`` False, nor a piece; ``cache_dir``: where its calibration is kept). Returns
    the recording, the response, the finished simulation and the Imitation."""
    from ..writing.brush_size import brush_for_char
    from ..writing.response import calibrate

    if progress is not None:
        progress(0.0, "reading the picture")
    im = read_picture(source, min(n_px, MAX_DETAIL), piece=piece)  # the writing is n_px
    if fit_brush and not piece and how.get("size_mm"):
        response = how.get("response") or calibrate(template, cache_dir=cache_dir)
        template, how["response"] = brush_for_char(
            template, response, im.char, how["size_mm"], cache_dir
        )
    if progress is not None:
        progress(0.05, f"{len(im.strokes)} strokes found; writing")

    def report(frac, *details):
        if progress is not None:
            progress(0.05 + 0.95 * frac, *details)

    rec, response, sim = write_imitation(im, template, n_px, progress=report, piece=piece, **how)
    return rec, response, sim, im


def write_imitation(
    im: Imitation,
    template,
    n_px: int = 512,
    size_mm: float | None = None,
    passes: int = PASSES,
    progress=None,
    px_per_mm: float | None = None,
    response=None,
    piece: bool = False,
    corrections: int = CORRECTIONS,
):
    """Write a picture's strokes as read (``im``) with the brush (``write_character``: press
    from the picture's widths, practice passes against the picture's own ink, each stroke
    landing on its start and practised to its ends) on an n_px sheet (0: the sheet of size_mm
    at px_per_mm, as Blender's Imitate Picture writes). While the written ink's shape agrees
    less than CORRECT_BELOW with the picture's, the best writing so far is read again against
    the picture's and the character written again with its stroke ends moved
    (``correct.corrected``; from the second time on, also the ends, corners and heads that set
    the box's sides), up to ``corrections`` times (a character written already is not written
    again: the same ink); the writing whose ink's shape agrees best with the picture's
    stays (``correct.shape_agreement``: both inks in their boxes, as imitations are measured;
    the Imitation's character data stays the strokes as read). Returns the recording, the
    response and the finished simulation."""
    from ..writing.writer import DIP_EVERY_STROKE, coverage_mask, write_character

    rounds = 1 + (corrections if not piece else 0)

    def writing(k):
        def report(frac, *details):
            if progress is not None:
                progress((k + frac) / rounds, *details)

        return report

    char, best = im.char, None
    tried = []  # the characters written so far: the same again would write the same ink
    for k in range(rounds):
        if char not in tried:  # (else: written already, bit for bit the same; best stays)
            tried.append(char)
            rec, response, sim = write_character(
                char,
                n_px,
                template,
                size_mm=size_mm,
                response=response,
                passes=passes,
                progress=writing(k),
                px_per_mm=px_per_mm,
                dip_every_mm=DIP_EVERY_STROKE,  # the picture's own tone, not the brush's
                exact_ends=True,  # the picture shows where each stroke's ink begins and ends
            )
            written = coverage_mask(sim)
            target = ink_on(im.ink.mask, len(written))  # the picture's ink on the sheet
            score = shape_agreement(written, target)
            if best is None or score > best[0]:
                best = (score, rec, sim, char, written)
            if score >= CORRECT_BELOW:
                break  # close enough: not written again
        if k + 1 == rounds:
            break
        # the best writing so far read again; from the second correction on, with its box
        _, _, _, base, seen = best
        scale = len(seen) / len(im.ink.mask)
        char = corrected(base, im.strokes, seen, target, scale, boxes=k > 0)
    if progress is not None:  # done, also when a writing was close enough before the last
        progress(1.0)
    _, rec, sim = best[:3]
    return rec, response, sim


def ink_on(mask: np.ndarray, n: int) -> np.ndarray:
    """A square mask (the ink read off a picture) on an n x n grid, each pixel the one under
    its centre (the ink read at MAX_DETAIL against a finer sheet)."""
    idx = ((np.arange(n) + 0.5) * len(mask) / n).astype(np.int64)
    return mask[idx[:, None], idx[None, :]]


# ------------------------------------------------------------------ against known data
def order_agreement(found: dict, known: dict, n: int = 512) -> dict:
    """How the strokes read off a picture agree with the character's known strokes: each found
    stroke is matched to the known stroke whose outline holds most of its median; ``pairs``
    is the share of pairs of found strokes (matched to different known ones) written in the
    known order, ``directions`` the share of matched strokes running the known way, ``same``
    whether the found strokes are the known ones in the known order."""
    from ..writing.outline import fill, resample, stroke_polygons, to_image

    masks = [fill([to_image(p, n) for p in polys], n) for polys in stroke_polygons(known)]
    match, runs = [], []
    for med in found["medians"]:
        pts = to_image(resample(np.array(med, dtype=float), 4.0)[0], n)
        iy = np.clip(pts[:, 1].astype(int), 0, n - 1)
        ix = np.clip(pts[:, 0].astype(int), 0, n - 1)
        share = [float(m[iy, ix].mean()) for m in masks]
        k = int(np.argmax(share))
        match.append(k if share[k] >= 0.5 else -1)
        kp, s = resample(np.array(known["medians"][k], dtype=float), 4.0)
        ends = np.array([med[0], med[-1]], dtype=float)
        near = np.argmin(np.linalg.norm(kp[None] - ends[:, None], axis=2), axis=1)
        runs.append(s[near[1]] > s[near[0]])
    pairs = [
        (match[i] < match[j])
        for i in range(len(match))
        for j in range(i + 1, len(match))
        if match[i] >= 0 and match[j] >= 0 and match[i] != match[j]
    ]
    matched = [r for r, m in zip(runs, match, strict=True) if m >= 0]
    return {
        "found": len(match),
        "known": len(masks),
        "pairs": float(np.mean(pairs)) if pairs else 1.0,
        "directions": float(np.mean(matched)) if matched else 0.0,
        "same": match == list(range(len(masks))),
    }
