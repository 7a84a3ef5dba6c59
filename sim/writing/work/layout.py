# SPDX-License-Identifier: GPL-3.0-or-later
"""Where the characters of a work go, in paper millimetres (x right, y up, as the engine's
paper; nothing here knows pixels, images or surfaces: on a 3D surface the same layout is laid
in the surface's UV space, mm / paper size).

A vertical work is written in columns from the top, read from right to left; a horizontal one
in rows from the left, read from top to bottom. Every character of the text has a square cell,
its em box (the 1024-unit box of the stroke data) at one size for the whole text, so a character
keeps its own extent in the box: 一 stays a line across the middle, 口 a small square, neither
is blown up to fill its cell. The columns (rows) are straight and evenly spaced. The signature
(落款) is smaller, in its own column left of the text (in a vertical work; in a row under it in a
horizontal one), starting lower than the text; the seal under it (after it). With a grid
(米字格 / 田字格) the cells are adjacent squares.

The layout is a record (``Layout``) that goes into the recording (``to_dict``/``from_dict``):
``next_place`` tells where text appended after the last character goes, so a work can be
continued, and every cell keeps its own box, so one can be written again."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field, replace

from ...core.params import ParameterError, number_within

VERTICAL, HORIZONTAL = "vertical", "horizontal"
DIRECTIONS = (VERTICAL, HORIZONTAL)
GRIDS = ("none", "mi", "tian")
TEXT, SIGNATURE, SEAL = "text", "signature", "seal"
# spacing, as shares of the text's em box (measured on classical works: characters close along a
# column, columns further apart; margins about a character)
ALONG_GAP = 0.14  # between characters of a line
ACROSS_GAP = 0.42  # between lines
GRID_PITCH = 1.22  # a grid's square boxes, adjacent
MARGIN = 0.8  # around the work when the paper is sized to it
PAPER_MARGIN = 0.075  # of the paper's shorter side, on a paper of a given size
SIGNATURE_SCALE = 0.5  # the signature's em box to the text's
SIGNATURE_GAP = 0.4  # between the text and the signature's line
SIGNATURE_DROP = 0.6  # the signature starts this much lower than the text (vertical)
SEAL_SCALE = 0.6  # the seal's side to the text's em box
SEAL_GAP = 0.45  # between the signature and the seal, in signature em boxes
PAPER_SIZES_MM = {  # portrait width x height
    "A5": (148.0, 210.0),
    "A4": (210.0, 297.0),
    "A3": (297.0, 420.0),
    "A2": (420.0, 594.0),
    "A1": (594.0, 841.0),
    "B4": (250.0, 353.0),
    "B3": (353.0, 500.0),
    "doufang": (690.0, 690.0),  # 四尺斗方
    "tiaofu": (345.0, 1380.0),  # 四尺对开条幅
    "zhongtang": (690.0, 1380.0),  # 四尺整张中堂
}


@dataclass
class Cell:
    """A written character's place: its em box's lower-left corner (paper mm) and side."""

    char: str
    role: str  # TEXT or SIGNATURE
    x: float
    y: float
    size: float
    line: int = 0  # the line (column or row) of the text; 0 for the signature
    index: int = 0  # its place in the line
    mark: bool = False  # a punctuation mark (written small in the cell's corner)
    seed: int = 0  # its own seed: variation and the brush's random stream (sim.writing.work)
    pad: tuple = (0.0, 0.0)  # half the gap to its neighbours, along and across its line
    # once written (sim.writing.work.compose): its samples [first, end) in the recording, the
    # brush's load at its start (share of a full dip), whether the brush was dipped for it, the
    # share of a load it used, and its variation (scale, slant deg, width, shift x, y in ems)
    samples: tuple = (0, 0)
    load: float = 1.0
    dip: bool = False
    used: float = 0.0
    variation: tuple = ()

    def box(self) -> tuple[float, float, float, float]:
        """(x0, y0, x1, y1) mm: the em box and half the gap to the neighbours around it."""
        return (self.x, self.y, self.x + self.size, self.y + self.size)

    def territory(self, vertical: bool) -> tuple[float, float, float, float]:
        along, across = self.pad
        px, py = (across, along) if vertical else (along, across)
        return (self.x - px, self.y - py, self.x + self.size + px, self.y + self.size + py)


@dataclass
class Layout:
    """The geometry of a work on its paper and the cells written so far (in writing order)."""

    direction: str
    width_mm: float
    height_mm: float
    char_mm: float  # the text's em box
    pitch_mm: float  # from a character to the next along a line
    line_mm: float  # from a line to the next
    per_line: int  # characters a line holds
    lines: int  # lines the paper holds
    origin: tuple  # (x, y) of line 0, place 0's em box's lower-left corner
    grid: str = "none"
    cells: list = field(default_factory=list)
    seal: dict | None = None  # {"text", "style", "box": [x0, y0, x1, y1] mm}

    @property
    def vertical(self) -> bool:
        return self.direction == VERTICAL

    def place(self, line: int, index: int) -> tuple[float, float]:
        """The lower-left corner of the em box at ``index`` of ``line``."""
        ox, oy = self.origin
        if self.vertical:
            return ox - line * self.line_mm, oy - index * self.pitch_mm
        return ox + index * self.pitch_mm, oy - line * self.line_mm

    def text_cells(self) -> list[Cell]:
        return [c for c in self.cells if c.role == TEXT]

    def reading_order(self) -> list[Cell]:
        """The text's cells in reading order, then the signature's."""
        key = {TEXT: 0, SIGNATURE: 1}
        return sorted(self.cells, key=lambda c: (key[c.role], c.line, c.index))

    def next_place(self, new_line: bool = False) -> tuple[int, int]:
        """(line, index) of the next character written after the last one of the text: the
        next place of its line, or the first of the next line when that is full or
        ``new_line``. (0, 0) on an empty work."""
        text = self.text_cells()
        if not text:
            return 0, 0
        last = max(text, key=lambda c: (c.line, c.index))
        if new_line or last.index + 1 >= self.per_line:
            return last.line + 1, 0
        return last.line, last.index + 1

    def grid_boxes(self) -> list[tuple[float, float, float, float]]:
        """Every place of the text's lines as a square box (the grid's), lines x per_line; [] for
        a work without a grid."""
        if self.grid == "none":
            return []
        used = max((c.line for c in self.text_cells()), default=0) + 1
        h = self.pitch_mm / 2.0
        out = []
        for line in range(used):
            for index in range(self.per_line):
                x, y = self.place(line, index)
                cx, cy = x + self.char_mm / 2.0, y + self.char_mm / 2.0
                out.append((cx - h, cy - h, cx + h, cy + h))
        return out

    def to_dict(self) -> dict:
        d = asdict(self)
        d["origin"] = list(self.origin)
        d["cells"] = [
            {
                **asdict(c),
                "pad": list(c.pad),
                "samples": list(c.samples),
                "variation": list(c.variation),
            }
            for c in self.cells
        ]
        return d

    @staticmethod
    def from_dict(d) -> Layout:
        """A layout from ``to_dict``'s values, checked (ParameterError names the field)."""
        if not isinstance(d, dict):
            raise ParameterError("'work.layout' must be an object")
        try:
            cells = [
                Cell(**{**c, **{k: tuple(c[k]) for k in ("pad", "samples", "variation") if k in c}})
                for c in d["cells"]
            ]
            lay = Layout(**{**d, "origin": tuple(d["origin"]), "cells": cells})
        except (KeyError, TypeError) as exc:
            raise ParameterError(f"'work.layout' is malformed: {exc}") from None
        _check(lay)
        return lay


def _check(lay: Layout) -> None:
    if lay.direction not in DIRECTIONS or lay.grid not in GRIDS:
        raise ParameterError(f"'work.layout': unknown direction or grid ({lay.direction!r})")
    nums = (lay.width_mm, lay.height_mm, lay.char_mm, lay.pitch_mm, lay.line_mm, *lay.origin)
    if not all(number_within(v, -1e6, 1e6) for v in nums) or lay.char_mm <= 0:
        raise ParameterError("'work.layout' has a size that is not a finite number")
    seal = lay.seal
    if seal is not None and not (
        isinstance(seal, dict)
        and isinstance(seal.get("text"), str)
        and seal.get("style") in ("baiwen", "zhuwen")
        and isinstance(seal.get("box"), list)
        and len(seal["box"]) == 4
        and all(number_within(v, -1e6, 1e6) for v in seal["box"])
    ):
        raise ParameterError("'work.layout.seal' must be {text, style (baiwen|zhuwen), box}")
    for c in lay.cells:
        ok = (
            isinstance(c.char, str)
            and len(c.char) == 1
            and c.role in (TEXT, SIGNATURE)
            and all(number_within(v, -1e6, 1e6) for v in (c.x, c.y, c.size, *c.pad))
            and c.size > 0
        )
        if not ok:
            raise ParameterError(f"'work.layout': a cell is malformed: {c!r}")


# ------------------------------------------------------------------------------ laying out
@dataclass
class Settings:
    """What the calligrapher chose: direction, characters a line (None: chosen to fit),
    signature, seal, grid, and either the em box in mm (``char_mm``; the paper fits the work)
    or the paper's size (``paper_mm``; the characters fit the paper), or both (a blank
    paper written from its corner, as the Blender operator does); neither: the caller chooses
    the em box (sim.writing.work.compose: the brush's own size)."""

    direction: str = VERTICAL
    per_line: int | None = None
    signature: str = ""
    seal: str = ""
    seal_style: str = "baiwen"
    grid: str = "none"
    char_mm: float | None = None
    paper_mm: tuple | None = None

    def check(self) -> None:
        if self.direction not in DIRECTIONS:
            raise ParameterError(f"layout must be one of {DIRECTIONS}, got {self.direction!r}")
        if self.grid not in GRIDS:
            raise ParameterError(f"grid must be one of {GRIDS}, got {self.grid!r}")
        if self.per_line is not None and not (
            isinstance(self.per_line, int) and 1 <= self.per_line <= 1000
        ):
            raise ParameterError(f"characters per line must be in [1, 1000], got {self.per_line}")


def _steps(char_mm: float, grid: str) -> tuple[float, float]:
    """(pitch along a line, between lines) for an em box of char_mm."""
    if grid != "none":
        return GRID_PITCH * char_mm, GRID_PITCH * char_mm
    return (1 + ALONG_GAP) * char_mm, (1 + ACROSS_GAP) * char_mm


def wrap(lines, per_line: int) -> list[list]:
    """The text's lines cut into lines of at most ``per_line`` glyphs (an empty line stays, an
    empty column of the work)."""
    out = []
    for line in lines:
        if not line:
            out.append([])
        for k in range(0, len(line), per_line):
            out.append(line[k : k + per_line])
    return out


SHORT_TEXT = 4


def auto_per_line(lines, vertical: bool) -> int:
    """Characters a line when the calligrapher did not say: the text's own lines when it has
    several (the longest), a short text (up to SHORT_TEXT) in one, else about a block a little
    taller than wide (vertical) or wider than tall (horizontal), the last line as full as the
    neighbouring choices allow."""
    if len(lines) > 1:
        return max(1, max(len(line) for line in lines))
    n = max(1, sum(len(line) for line in lines))
    if n <= SHORT_TEXT:  # a word or an idiom: one line (a 横幅, a column of 四字)
        return n
    ratio = 1.35 if vertical else 1.0 / 1.35  # characters along / lines
    best = max(1, round(math.sqrt(n * ratio * (1 + ACROSS_GAP) / (1 + ALONG_GAP))))
    options = [p for p in (best - 1, best, best + 1) if p >= 1]
    return min(options, key=lambda p: ((-n) % p, abs(p - best), -p))


def _signature_length(settings: Settings, char_mm: float) -> float:
    """Along its line: the signature's characters and the seal after them (mm)."""
    sig = SIGNATURE_SCALE * char_mm
    length = len(settings.signature) * sig * (1 + ALONG_GAP)
    if settings.seal:
        length += (SEAL_GAP * sig if settings.signature else 0.0) + SEAL_SCALE * char_mm
    return length


def _extent(settings: Settings, n_lines: int, per_line: int, char_mm: float):
    """(along, across) mm of the text and its signature, and the signature's own offset across."""
    pitch, line = _steps(char_mm, settings.grid)
    box = char_mm if settings.grid == "none" else pitch  # a grid's boxes surround the em box
    along = (per_line - 1) * pitch + box
    across = (n_lines - 1) * line + box
    if settings.signature or settings.seal:
        drop = SIGNATURE_DROP * char_mm if settings.direction == VERTICAL else 0.0
        along = max(along, drop + _signature_length(settings, char_mm))
        across += SIGNATURE_GAP * char_mm + max(
            SIGNATURE_SCALE * char_mm, SEAL_SCALE * char_mm if settings.seal else 0.0
        )
    return along, across


def _fit(settings: Settings, lines) -> tuple[float, int, float]:
    """(char_mm, per_line, margin) on a paper of the given size: the largest em box with which
    the work fits inside the margins, over every number of characters a line (or the one
    given)."""
    w, h = settings.paper_mm
    margin = PAPER_MARGIN * min(w, h)
    aw, ah = w - 2 * margin, h - 2 * margin
    vertical = settings.direction == VERTICAL
    longest = max((len(line) for line in lines), default=1) or 1
    candidates = [settings.per_line] if settings.per_line else range(1, longest + 1)
    best = None
    for p in candidates:
        n_lines = max(len(wrap(lines, p)), 1)
        along, across = _extent(settings, n_lines, p, 1.0)  # linear in the em box
        room_along, room_across = (ah, aw) if vertical else (aw, ah)
        size = min(room_along / along, room_across / across)
        if best is None or size > best[0] * (1 + 1e-9):
            best = (size, p)
    return best[0], best[1], margin


def lay_out(lines, settings: Settings) -> Layout:
    """The layout of a work: the text's ``lines`` (sim.writing.work.text) in cells, the
    signature and the seal. On a paper of a given size, without a character size, the
    characters are as large as fit and the work is centred; with both, the work starts at the
    paper's top right (vertical) or top left (horizontal) inside its margins, its lines as
    long as the paper holds, room left for more; with a character size only, the paper is the
    work and its margins. Raises ParameterError."""
    settings.check()
    if settings.char_mm is None and settings.paper_mm is None:
        raise ParameterError("give the character size or the paper's size")
    vertical = settings.direction == VERTICAL
    blank = settings.paper_mm is not None and settings.char_mm is not None
    if blank:
        char_mm = float(settings.char_mm)
        w, h = settings.paper_mm
        margin = PAPER_MARGIN * min(w, h)
        pitch, _ = _steps(char_mm, settings.grid)
        room = (h if vertical else w) - 2 * margin
        box = char_mm if settings.grid == "none" else pitch
        per_line = settings.per_line or max(int((room - box) // pitch) + 1, 1)
    elif settings.paper_mm is not None:
        char_mm, per_line, margin = _fit(settings, lines)
        w, h = settings.paper_mm
    else:
        char_mm = float(settings.char_mm)
        per_line = settings.per_line or auto_per_line(lines, vertical)
        margin = MARGIN * char_mm
    rows = wrap(lines, per_line) or [[]]
    along, across = _extent(settings, len(rows), per_line, char_mm)
    if settings.paper_mm is None:
        w, h = (across, along) if vertical else (along, across)
        w, h = w + 2 * margin, h + 2 * margin
    pitch, line_mm = _steps(char_mm, settings.grid)
    inset = (pitch - char_mm) / 2 if settings.grid != "none" else 0.0
    ext_w, ext_h = (across, along) if vertical else (along, across)
    if blank:  # from the corner where the writing starts
        left = w - margin - ext_w if vertical else margin
        bottom = h - margin - ext_h
    else:  # the work centred on the paper (on a paper sized to it: at its margins)
        left, bottom = (w - ext_w) / 2, (h - ext_h) / 2
    if vertical:  # columns from the right edge of the work, from its top
        origin = (left + ext_w - inset - char_mm, bottom + ext_h - inset - char_mm)
    else:
        origin = (left + inset, bottom + ext_h - inset - char_mm)
    room = (w - 2 * margin) if vertical else (h - 2 * margin)
    capacity = max(len(rows), int((room - char_mm) // line_mm) + 1, 1)
    lay = Layout(settings.direction, w, h, char_mm, pitch, line_mm, per_line, capacity, origin)
    lay.grid = settings.grid
    pad = ((pitch - char_mm) / 2, (line_mm - char_mm) / 2)
    seed = 0
    for n, row in enumerate(rows):
        for k, g in enumerate(row):
            if g.kind == "space":
                continue
            x, y = lay.place(n, k)
            lay.cells.append(Cell(g.text, TEXT, x, y, char_mm, n, k, g.kind == "mark", seed, pad))
            seed += 1
    _sign(lay, settings, len(rows), seed, left + ext_w)
    if w > 1e5 or h > 1e5:
        raise ParameterError(f"the work is {w:.0f} x {h:.0f} mm: too large")
    if blank:
        _check_on_paper(lay)
    return lay


def _check_on_paper(lay: Layout) -> None:
    """Every cell and the seal on the paper (ParameterError naming how many are not)."""
    boxes = [c.box() for c in lay.cells] + ([tuple(lay.seal["box"])] if lay.seal else [])
    off = sum(
        not (
            -1e-6 <= x0 and x1 <= lay.width_mm + 1e-6 and -1e-6 <= y0 and y1 <= lay.height_mm + 1e-6
        )
        for x0, y0, x1, y1 in boxes
    )
    if off:
        raise ParameterError(
            f"the work does not fit the paper: {off} of its {len(boxes)} characters and seal "
            "would fall off it (a larger paper, a smaller size, or more characters a line)"
        )


def _sign(lay: Layout, settings: Settings, n_rows: int, seed: int, right_edge: float) -> None:
    """The signature's cells and the seal, after the text's ``n_rows`` lines (``right_edge``:
    the work's, where a horizontal work's signature line ends)."""
    if not (settings.signature or settings.seal):
        return
    c = lay.char_mm
    sig = SIGNATURE_SCALE * c
    step = sig * (1 + ALONG_GAP)
    seal = SEAL_SCALE * c
    width = max(sig, seal if settings.seal else 0.0)  # the signature line's width across
    x_last, y_last = lay.place(n_rows - 1, 0)
    inset = (lay.pitch_mm - c) / 2 if lay.grid != "none" else 0.0
    pad = ((step - sig) / 2, SIGNATURE_GAP * c / 2)
    n = len(settings.signature)
    if lay.vertical:  # a column left of the text's last, starting lower than the text
        cx = x_last - inset - SIGNATURE_GAP * c - width / 2
        top = y_last + c + inset - SIGNATURE_DROP * c
        places = [(cx - sig / 2, top - (k + 1) * step + (step - sig) / 2) for k in range(n)]
        y1 = top - n * step - (SEAL_GAP * sig if n else 0.0)
        box = (cx - seal / 2, y1 - seal, cx + seal / 2, y1)
    else:  # a row under the text's last, ending (with the seal) at the work's right edge
        cy = y_last - inset - SIGNATURE_GAP * c - width / 2
        start = right_edge - _signature_length(settings, c)
        places = [(start + k * step + (step - sig) / 2, cy - sig / 2) for k in range(n)]
        box = (right_edge - seal, cy - seal / 2, right_edge, cy + seal / 2)
    for k, (ch, (x, y)) in enumerate(zip(settings.signature, places, strict=True)):
        lay.cells.append(Cell(ch, SIGNATURE, x, y, sig, 0, k, False, seed + k, pad))
    if settings.seal:
        lay.seal = {"text": settings.seal, "style": settings.seal_style, "box": list(box)}


def sign(lay: Layout, signature: str, seal: str = "", seal_style: str = "baiwen") -> list[Cell]:
    """Add the signature's cells (returned) and the seal after the work's text as it is now,
    on its paper (ParameterError when they would fall off it, or the work is signed)."""
    if lay.seal or any(c.role != TEXT for c in lay.cells):
        raise ParameterError("the work is signed already")
    text = lay.text_cells()
    n_rows = max((c.line for c in text), default=0) + 1
    inset = (lay.pitch_mm - lay.char_mm) / 2 if lay.grid != "none" else 0.0
    box = lay.char_mm + 2 * inset
    right = lay.origin[0] - inset + (lay.per_line - 1) * lay.pitch_mm + box  # horizontal work
    before = len(lay.cells)
    seed = max((c.seed for c in lay.cells), default=-1) + 1
    settings = Settings(lay.direction, signature=signature, seal=seal, seal_style=seal_style)
    _sign(lay, settings, n_rows, seed, right)
    _check_on_paper(lay)
    return lay.cells[before:]


def paper_size(name: str, landscape: bool) -> tuple[float, float]:
    """A named paper (``PAPER_SIZES_MM``) or ``WxH`` in mm, as (width, height)."""
    key = {k.lower(): k for k in PAPER_SIZES_MM}.get(name.strip().lower())
    if key is not None:
        w, h = PAPER_SIZES_MM[key]
        return (h, w) if landscape and h > w else (w, h)
    try:
        w, h = (float(v) for v in name.lower().split("x"))
    except ValueError:
        raise ParameterError(
            f"unknown paper {name!r}: one of {', '.join(PAPER_SIZES_MM)}, or WxH in mm"
        ) from None
    if not (number_within(w, 10.0, 5000.0) and number_within(h, 10.0, 5000.0)):
        raise ParameterError(f"a paper of {name} mm: each side must lie in [10, 5000] mm")
    return w, h


def moved(cell: Cell, **changes) -> Cell:
    return replace(cell, **changes)
