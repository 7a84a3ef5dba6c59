# SPDX-License-Identifier: GPL-3.0-or-later
"""The text of a work as the calligrapher reads it: lines (a newline starts a new column, or
row), each a list of glyphs - characters to write, punctuation marks (left out by default, as in
classical works, or written small in their cell's corner), spaces (an empty cell) - and the
characters that have no stroke data, named each of them in one message."""

from __future__ import annotations

import unicodedata
from typing import NamedTuple

from ...core.params import ParameterError
from ..hanzi import lookup
from .marks import MARKS

CHAR, MARK, SPACE = "char", "mark", "space"
PUNCTUATION_MODES = ("omit", "keep")
MAX_TEXT_CHARS = 20_000  # glyphs of one work (the 千字文 is 1,000)


class Glyph(NamedTuple):
    text: str  # one character
    kind: str  # CHAR, MARK or SPACE


class MissingCharacters(ParameterError):
    """Characters of the text that have no stroke data; ``chars`` lists each once, in order."""

    def __init__(self, chars: list[str], data=None):
        self.chars = list(chars)
        names = ", ".join(describe(c) for c in self.chars)
        where = f"{data} or the bundled set" if data else "the bundled set"
        super().__init__(
            f"no stroke data for {len(self.chars)} character(s) of the text: {names} (not in "
            f"{where}). Nothing was written: leave them out with --skip-missing, or give --data "
            "(a graphics.txt or a folder of <char>.json) that has them"
        )


def describe(c: str) -> str:
    """'A' (U+0041 LATIN CAPITAL LETTER A): a character as a message names it."""
    name = unicodedata.name(c, "")
    return f"{c!r} (U+{ord(c):04X}{' ' + name if name else ''})"


def is_punctuation(c: str) -> bool:
    return unicodedata.category(c).startswith("P") or c in MARKS


def parse_text(text: str, punctuation: str = "omit") -> list[list[Glyph]]:
    """The lines of ``text``: a newline ends a line (a column of a vertical work, a row of a
    horizontal one); trailing blank lines go; a space (ASCII or ideographic) is an empty cell;
    punctuation is left out (``omit``) or kept as marks (``keep``). Raises ParameterError."""
    if not isinstance(text, str):
        raise ParameterError("the text must be a string")
    if punctuation not in PUNCTUATION_MODES:
        raise ParameterError(f"punctuation must be one of {PUNCTUATION_MODES}, got {punctuation!r}")
    lines, cur = [], []
    for c in text.replace("\r\n", "\n").replace("\r", "\n"):
        if c == "\n":
            lines.append(cur)
            cur = []
        elif c.isspace():
            cur.append(Glyph(" ", SPACE))
        elif unicodedata.category(c) in ("Cc", "Cf", "Mn", "Me", "Cs"):
            continue  # control, format (zero-width joiners, variation selectors), combining
        elif is_punctuation(c):
            if punctuation == "keep":
                cur.append(Glyph(c, MARK))
        else:
            cur.append(Glyph(c, CHAR))
    lines.append(cur)
    lines = [_strip(line) for line in lines]
    while lines and not lines[-1]:
        lines.pop()
    count = sum(len(line) for line in lines)
    if count > MAX_TEXT_CHARS:
        raise ParameterError(f"the text has {count} characters; at most {MAX_TEXT_CHARS}")
    return lines


def _strip(line: list[Glyph]) -> list[Glyph]:
    """A line without its trailing spaces."""
    while line and line[-1].kind == SPACE:
        line = line[:-1]
    return line


def missing_characters(lines, data=None) -> list[str]:
    """Each character of the lines without stroke data (nor a mark's shape), once, in order."""
    out, seen = [], set()
    for line in lines:
        for g in line:
            if g.text in seen or g.kind == SPACE:
                continue
            seen.add(g.text)
            if g.kind == MARK and g.text not in MARKS:
                out.append(g.text)
            elif g.kind == CHAR and lookup(g.text, data) is None:
                out.append(g.text)
    return out


def drop(lines, chars) -> list[list[Glyph]]:
    """The lines without the glyphs ``chars`` (the missing ones, when they are to be skipped)."""
    gone = set(chars)
    return [_strip([g for g in line if g.text not in gone]) for line in lines]


def writable(text: str) -> bool:
    """True when ``text`` has a glyph to write (not only spaces and left-out punctuation)."""
    return any(g.kind != SPACE for line in parse_text(text) for g in line)
