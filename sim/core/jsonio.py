# SPDX-License-Identifier: GPL-3.0-or-later
"""Reading the engine's JSON files (recordings, character data, quality files, presets) so that
every bad file ends in one message naming it: too large, not UTF-8 text, not JSON, nested too
deeply. The caller's error type carries the message."""

from __future__ import annotations

import json
from pathlib import Path

MAX_JSON_BYTES = 256 * 2**20  # a 2M-sample recording is about 150 MB
_UTF16_32_BOMS = (b"\xff\xfe", b"\xfe\xff", b"\x00\x00\xfe\xff")


def decode_text(data: bytes, where: str, error=ValueError) -> str:
    """UTF-8 text (a leading byte-order mark is dropped); anything else is refused."""
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    elif data.startswith(_UTF16_32_BOMS):
        raise error(f"{where} is UTF-16 or UTF-32 text; save it as UTF-8")
    if b"\x00" in data:  # never in JSON text; UTF-16 without a byte-order mark
        raise error(f"{where} is not UTF-8 text (it holds NUL bytes: UTF-16?)")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise error(f"{where} is not UTF-8 text (bad byte at offset {exc.start})") from None


def parse_json(text: str, where: str, error=ValueError):
    """JSON text -> Python values; NaN and Infinity come through as floats for the caller's
    checks to refuse by name."""
    try:
        return json.loads(text)
    except json.JSONDecodeError as exc:
        raise error(f"{where} is not valid JSON: {exc}") from None
    except RecursionError:
        raise error(f"{where} is nested too deeply to be read") from None
    except ValueError as exc:  # e.g. an integer of more than 4300 digits
        raise error(f"{where} is not valid JSON: {exc}") from None


def read_json(path, what: str, error=ValueError, max_bytes: int = MAX_JSON_BYTES):
    """The JSON values in the file at ``path``; ``what`` names the kind of file in messages."""
    p = Path(path)
    where = f"{what} {p}"
    try:
        if not p.is_file():
            raise error(f"{where} does not exist or is not a file")
        size = p.stat().st_size
        if size > max_bytes:
            raise error(f"{where} is too large ({size} bytes; at most {max_bytes})")
        data = p.read_bytes()
    except OSError as exc:
        raise error(f"cannot read {where}: {exc.strerror or exc}") from None
    return parse_json(decode_text(data, where, error), where, error)
