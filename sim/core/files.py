# SPDX-License-Identifier: GPL-3.0-or-later
"""Writing a file whole or not at all (issue 30): every file the project writes (PNGs,
recordings, write-set's JSON, the farm cache, presets, exports, image sequences) goes to a
temporary name beside the target, is flushed to the disk, and only then takes the target's name
with ``os.replace`` (atomic on POSIX and Windows within one folder). A full disk, a file-size
limit, an error in the middle or a kill leaves the previous file as it was; only a stray
temporary file (``.NAME.*.tmp``, removed on any error Python sees) can be left by a kill."""

from __future__ import annotations

import contextlib
import errno
import os
import secrets
import stat
from collections.abc import Callable
from typing import BinaryIO

TEMP_SUFFIX = ".tmp"


class WriteError(OSError):
    """A file could not be written; whatever was at its path before is unchanged."""

    def __str__(self) -> str:
        return f"cannot write {self.filename}: {self.strerror} (any earlier file there is kept)"


def temp_name(path) -> str:
    """A fresh hidden name beside ``path`` (same folder, so os.replace stays atomic)."""
    folder, name = os.path.split(os.fspath(path))
    return os.path.join(folder, f".{name}.{os.getpid()}.{secrets.token_hex(4)}{TEMP_SUFFIX}")


def _target(path) -> str:
    """Where the bytes go: a symbolic link is written through, as ``open(path, 'w')`` does."""
    path = os.fspath(path)
    return os.path.realpath(path) if os.path.islink(path) else path


def _open_temp(target: str) -> tuple[int, str]:
    """A new temporary file beside ``target``, created with the permissions a plain open
    gives (0o666 less the umask), or the target's own when it exists."""
    for _ in range(16):
        tmp = temp_name(target)
        try:
            flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0)
            fd = os.open(tmp, flags, 0o666)
        except FileExistsError:
            continue
        with contextlib.suppress(OSError):
            os.chmod(tmp, stat.S_IMODE(os.stat(target).st_mode))
        return fd, tmp
    raise FileExistsError(f"cannot find a free temporary name beside {target}")


def _sync_folder(folder: str) -> None:
    """Make the rename itself durable where the system allows opening a folder (POSIX)."""
    try:
        fd = os.open(folder or ".", os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def write_atomic(path, data: bytes | str | Callable[[BinaryIO], None]) -> None:
    """Write ``data`` (bytes, text as UTF-8, or a function writing to the open binary file)
    to ``path`` whole or not at all. On any failure (full disk, ``ulimit -f``, an exception of
    the writer) the temporary file is removed, the previous file at ``path`` is untouched, and
    an OSError is raised again as ``WriteError`` naming ``path``."""
    target = _target(path)
    if os.path.isdir(target):
        raise WriteError(errno.EISDIR, "it is a folder", os.fspath(path))
    try:
        fd, tmp = _open_temp(target)
    except OSError as exc:
        raise WriteError(exc.errno, exc.strerror or str(exc), os.fspath(path)) from None
    try:
        with os.fdopen(fd, "wb") as f:
            if callable(data):
                data(f)
            else:
                f.write(data.encode("utf-8") if isinstance(data, str) else data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, target)
    except BaseException as exc:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        if isinstance(exc, OSError) and not isinstance(exc, WriteError):
            raise WriteError(exc.errno, exc.strerror or str(exc), os.fspath(path)) from None
        raise
    _sync_folder(os.path.dirname(target))


def write_json_atomic(path, obj, **dump_options) -> None:
    """``obj`` as compact JSON (UTF-8), written with ``write_atomic``; NaN and infinities are
    refused (ValueError) rather than written as JSON no reader accepts."""
    import json

    options = {"separators": (",", ":"), "allow_nan": False, **dump_options}
    write_atomic(path, json.dumps(obj, **options))
