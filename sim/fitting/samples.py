# SPDX-License-Identifier: GPL-3.0-or-later
"""Training samples (Sec. 7.2): a recording and the image S^i it should have made, from stroke
data (the writer's recording against the font's outline in the template's ink on its paper)
or from the user's own image and the recording that goes with it."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.params import ParameterError
from ..core.recording import Recording

TRAINING_SIZE_PX = 96  # a training character's image size, unless chosen (CLI and Blender)


@dataclass
class TrainingSample:
    """One training pair: a recording and the image S^i (H, W, 3) in [0, 1], top row first, at
    the recording's paper size."""

    recording: Recording
    target: np.ndarray
    name: str = ""
    # Sec. 7.2's two classes of training samples: "shape" (boundaries only, fits Qp1 with
    # Qp2 = 0), "texture" (fits Qp2); "both" serves either stage
    kind: str = "both"

    def __post_init__(self):
        t = np.asarray(self.target, dtype=np.float32)
        if t.ndim != 3 or t.shape[2] != 3:
            raise ParameterError(f"training sample {self.name!r}: image must be (H, W, 3) RGB")
        h, w = self.recording.height_px, self.recording.width_px
        if t.shape[:2] != (h, w):
            raise ParameterError(
                f"training sample {self.name!r}: image is {t.shape[1]} x {t.shape[0]} px but "
                f"its recording's paper is {w} x {h} px"
            )
        self.target = t
        if self.kind not in ("shape", "texture", "both"):
            raise ParameterError(f"training sample {self.name!r}: kind must be shape or texture")


def ink_image(mask, paper_rgb, ink_rgb) -> np.ndarray:
    """S^i from a boundary: ink colour inside, paper colour outside; (H, W, 3) float32."""
    m = np.asarray(mask, dtype=np.float32)[..., None]
    return (
        np.asarray(paper_rgb, np.float32) * (1 - m) + np.asarray(ink_rgb, np.float32) * m
    ).astype(np.float32)


def character_samples(
    chars: list[dict], n_px: int, template: Recording, names=None, passes=1, response=None
):
    """Training samples from stroke data: the outline is the boundary, the median the path. The
    recording is what the writer (``sim.writing``) makes with the template's settings; the
    target is the font's character in the template's ink on its paper."""
    from ..writing.writer import font_mask, write_character

    out = []
    for k, ch in enumerate(chars):
        rec, response, sim = write_character(ch, n_px, template, response=response, passes=passes)
        target = ink_image(font_mask(ch, n_px), sim.paper.color, sim.ink.color)
        out.append(TrainingSample(rec, target, (names or [""] * len(chars))[k]))
    return out


def image_sample(recording: Recording, png_path, name: str = "") -> TrainingSample:
    """A training sample from the user's own image and the recording that goes with it; the
    image's size is checked against the recording's paper before it is decoded."""
    from ..image.png import png_header, read_png

    w, h, _ = png_header(png_path)
    if (w, h) != (recording.width_px, recording.height_px):
        raise ParameterError(
            f"image {png_path} is {w} x {h} px but its recording's paper is "
            f"{recording.width_px} x {recording.height_px} px"
        )
    a = read_png(png_path).astype(np.float32) / 255.0
    if a.shape[2] <= 2:  # grey, grey + alpha
        a = np.repeat(a[..., :1], 3, axis=2)
    return TrainingSample(recording, a[..., :3], name or str(png_path))
