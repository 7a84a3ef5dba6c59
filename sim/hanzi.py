# SPDX-License-Identifier: GPL-3.0-or-later
"""Character stroke data (hanzi-writer-data / Make Me a Hanzi): medians as brush paths.

Coordinates in the data: a 1024-unit em box, y up, with image y = 900 - y_data. On the paper
(mm, y up) the em box maps onto a square of ``size_mm`` whose top edge is y_data = 900."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from .strokes import stroke, travel

EM = 1024.0
TOP = 900.0


def load_char(path) -> dict:
    p = Path(path)
    try:
        d = json.loads(p.read_text(encoding="utf-8"))
    except (OSError, json.JSONDecodeError) as exc:
        raise ValueError(f"cannot read character data {p}: {exc}") from None
    if not isinstance(d, dict) or "medians" not in d or "strokes" not in d:
        raise ValueError(f"{p}: not hanzi-writer data (needs 'strokes' and 'medians')")
    return d


DATA_DIR = Path(__file__).resolve().parent.parent / "data" / "hanzi"


def find_char(spec: str, data=None) -> dict:
    """Character data from a path to a hanzi-writer JSON file, or from a character looked up in
    ``data``: a folder of hanzi-writer-data files (``<char>.json``) or Make Me a Hanzi's
    ``graphics.txt`` (one JSON object per line with a "character" key). Without ``data`` the
    characters bundled with the add-on are searched."""
    p = Path(spec)
    if p.suffix == ".json" and p.is_file():
        return load_char(p)
    if len(spec) != 1:
        raise ValueError(f"{spec!r} is neither a character data file nor a single character")
    src = Path(data) if data else DATA_DIR
    if src.is_dir():
        f = src / f"{spec}.json"
        if not f.is_file():
            raise ValueError(f"no data for {spec!r} in {src} (looked for {f.name})")
        return load_char(f)
    if src.is_file():
        key = f'"character":"{spec}"'
        with open(src, encoding="utf-8") as fh:
            for line in fh:
                if key in line.replace(" ", ""):
                    try:
                        d = json.loads(line)
                    except json.JSONDecodeError as exc:
                        raise ValueError(f"{src}: bad line for {spec!r}: {exc}") from None
                    if d.get("character") == spec and "strokes" in d and "medians" in d:
                        return d
        raise ValueError(f"no data for {spec!r} in {src}")
    raise ValueError(f"character data {src} does not exist")


def to_paper(points, size_mm: float, origin=(0.0, 0.0)) -> np.ndarray:
    """Data units -> paper mm (y up): the em box [0, 1024] x [900 - 1024, 900] fills the square."""
    pts = np.asarray(points, dtype=float)
    s = size_mm / EM
    return np.stack([origin[0] + pts[:, 0] * s, origin[1] + (pts[:, 1] - (TOP - EM)) * s], axis=1)


def simple_samples(
    char: dict,
    size_mm: float,
    hair_length_mm: float,
    press_mm: float = 9.0,
    speed_mm_s: float = 70.0,
    rate_hz: float = 120.0,
) -> np.ndarray:
    """A plain trajectory: each median written at constant press, the brush lifted between."""
    hover = hair_length_mm + 4.0
    parts, prev = [], None
    for med in char["medians"]:
        pts = to_paper(med, size_mm)
        if prev is not None:
            parts.append(travel(prev, pts[0], 20, hover))
        parts.append(
            stroke(
                pts,
                rate_hz=rate_hz,
                speed_mm_s=speed_mm_s,
                press_mm=press_mm,
                hair_length_mm=hair_length_mm,
            )
        )
        prev = pts[-1]
    return np.concatenate(parts)


def character_recording(path, size_mm: float = 160.0, px_per_mm: float = 6.0):
    """The demo's recording: one character written by the soft goat-hair brush on raw xuan."""
    from .recording import Dip, Recording

    samples = simple_samples(load_char(path), size_mm, hair_length_mm=34.0, press_mm=14.0)
    return Recording(
        samples,
        width_mm=size_mm,
        height_mm=size_mm,
        px_per_mm=px_per_mm,
        brush={"preset": "goat_soft"},
        paper_preset="raw_xuan",
        dips=[Dip(0, 0.9, (0.03, 0.03, 0.04), 0.95)],
    )
