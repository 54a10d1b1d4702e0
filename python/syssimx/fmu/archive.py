"""FMU archives: checked before anything is read from them, extracted without escaping.

Every problem with an archive is an FMUFileError naming the file: a missing or non-zip file, an
entry that would land outside the extraction folder (absolute path, "..", symlink), a name the
file system cannot hold, a corrupt member, or content larger than the size limit.

The size limit guards against zip bombs (a few MB of archive that inflate to GBs). It is
checked twice: against the sizes the archive declares, before anything is written, and against
the bytes actually inflated while extracting. It defaults to DEFAULT_SIZE_LIMIT (4 GiB) and is
overridden with the environment variable SYSSIMX_FMU_SIZE_LIMIT (bytes), read at each load.
"""

from __future__ import annotations

import os
import re
import shutil
import stat
import zipfile
import zlib
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from ..errors import ConfigurationError, FMUFileError

DEFAULT_SIZE_LIMIT = 4 * 2**30
SIZE_LIMIT_VARIABLE = "SYSSIMX_FMU_SIZE_LIMIT"
NAME_MAX = 255  # bytes per path component on the file systems syssimx runs on
_CHUNK = 2**20
_DRIVE = re.compile(r"^[A-Za-z]:")
_ENCRYPTED = 0x1  # bit 0 of a zip entry's general purpose flags
# the compression methods Python's zipfile inflates; other archivers may write Deflate64 (9)
_INFLATABLE = (zipfile.ZIP_STORED, zipfile.ZIP_DEFLATED, zipfile.ZIP_BZIP2, zipfile.ZIP_LZMA)
_METHOD_NAMES = {9: "Deflate64 (method 9)"}


def size_limit(path: Path) -> int:
    """The most bytes the FMU archive at `path` may inflate to."""
    text = os.environ.get(SIZE_LIMIT_VARIABLE)
    if text is None:
        return DEFAULT_SIZE_LIMIT
    try:
        limit = int(text)
    except ValueError:
        limit = -1
    if limit <= 0:
        raise ConfigurationError(f"{path}: cannot check the archive's size: "
                                 f"{SIZE_LIMIT_VARIABLE}={text!r} is not a positive number of "
                                 "bytes")
    return limit


def _shown(name: str) -> str:
    return repr(name if len(name) <= 80 else name[:77] + "...")


@contextmanager
def open_archive(path: Path) -> Iterator[zipfile.ZipFile]:
    """The archive at `path`, its entries checked (names, kinds, declared sizes)."""
    if not path.is_file():
        raise FMUFileError(f"FMU file not found: {path}")
    try:
        archive = zipfile.ZipFile(path)
    except (zipfile.BadZipFile, OSError, ValueError, EOFError) as exc:
        raise FMUFileError(f"{path} is not an FMU: the file is not a readable zip archive "
                           f"({exc or type(exc).__name__})") from exc
    with archive:
        check_entries(archive, path)
        yield archive


def check_entries(archive: zipfile.ZipFile, path: Path) -> None:
    """Refuse entries that would escape the extraction folder and content above the limit."""
    limit = size_limit(path)
    total = 0
    for info in archive.infolist():
        name = info.filename
        problem = _entry_problem(info)
        if problem:
            raise FMUFileError(f"{path}: archive entry {_shown(name)} {problem}")
        total += info.file_size
        if total > limit:
            raise FMUFileError(f"{path}: the archive inflates to more than {limit} bytes (the "
                               f"limit; raise it with {SIZE_LIMIT_VARIABLE})")


def _entry_problem(info: zipfile.ZipInfo) -> str:
    name = info.filename
    if name.startswith(("/", "\\")) or _DRIVE.match(name):
        return "has an absolute path"
    parts = name.split("/")
    if ".." in parts:
        return "climbs out of the archive with '..'"
    if stat.S_ISLNK(info.external_attr >> 16):
        return "is a symbolic link"
    if any(len(part.encode()) > NAME_MAX for part in parts):
        return f"has a name component longer than {NAME_MAX} bytes"
    if info.flag_bits & _ENCRYPTED:
        return "is encrypted: syssimx reads no password-protected archive"
    if info.compress_type not in _INFLATABLE:
        method = _METHOD_NAMES.get(info.compress_type, f"method {info.compress_type}")
        return f"is compressed with {method}, which syssimx cannot inflate (repack it with Deflate)"
    return ""


def extract(path: Path, directory: Path) -> None:
    """Extract the archive at `path` into the existing, empty `directory`, counting the bytes
    inflated against the size limit. On failure the directory is removed."""
    try:
        with open_archive(path) as archive:
            limit = size_limit(path)
            written = 0
            root = directory.resolve()
            for info in archive.infolist():
                target = (directory / info.filename).resolve()
                if not target.is_relative_to(root):
                    raise FMUFileError(f"{path}: archive entry {_shown(info.filename)} lands "
                                       "outside the extraction folder")
                if info.is_dir():
                    target.mkdir(parents=True, exist_ok=True)
                    continue
                target.parent.mkdir(parents=True, exist_ok=True)
                written = _copy_member(archive, info, target, written, limit, path)
    except FMUFileError:
        shutil.rmtree(directory, ignore_errors=True)
        raise
    except (zipfile.BadZipFile, zlib.error, EOFError, NotImplementedError) as exc:
        shutil.rmtree(directory, ignore_errors=True)
        raise FMUFileError(f"{path}: corrupt archive: {exc or type(exc).__name__}") from exc
    except OSError as exc:
        shutil.rmtree(directory, ignore_errors=True)
        raise FMUFileError(f"{path}: cannot extract the archive: {exc}") from exc


def _copy_member(archive: zipfile.ZipFile, info: zipfile.ZipInfo, target: Path, written: int,
                 limit: int, path: Path) -> int:
    try:
        with archive.open(info) as source, open(target, "wb") as sink:
            while chunk := source.read(_CHUNK):
                written += len(chunk)
                if written > limit:
                    raise FMUFileError(f"{path}: the archive inflates to more than {limit} "
                                       f"bytes (the limit; raise it with {SIZE_LIMIT_VARIABLE})")
                sink.write(chunk)
    except (zipfile.BadZipFile, zlib.error, EOFError) as exc:
        raise FMUFileError(f"{path}: corrupt archive member {_shown(info.filename)}: "
                           f"{exc or type(exc).__name__}") from exc
    return written
