"""A modelDescription in the encoding it declares, as the UTF-8 the engine's reader reads.

FMI prescribes UTF-8, but tools write others (20-sim: ISO-8859-1) and FMPy, libcosim and
OMSimulator read them. The encoding is what a byte order mark says, else what the XML
declaration names (XML 1.0, appendix F); the text is decoded strictly, so only bytes invalid
in that encoding are refused, and handed on re-encoded as UTF-8 with a declaration saying so.
"""

from __future__ import annotations

import codecs
import re
from pathlib import Path

from ..errors import FMUFileError

# the byte order marks and the first characters "<?" of each UTF-16/32 form, by codec
_MARKS = ((codecs.BOM_UTF32_LE, "utf-32"), (codecs.BOM_UTF32_BE, "utf-32"),
          (codecs.BOM_UTF8, "utf-8"), (codecs.BOM_UTF16_LE, "utf-16"),
          (codecs.BOM_UTF16_BE, "utf-16"), (b"<\0?\0", "utf-16-le"), (b"\0<\0?", "utf-16-be"))
_DECLARATION = re.compile(rb"""<\?xml\s[^>]*?\bencoding\s*=\s*(["'])([A-Za-z][\w.:-]*)\1""")
_DECLARED_TEXT = re.compile(r"""(<\?xml\s[^>]*?\bencoding\s*=\s*)(["'])[^"']*\2""")
# what the engine reads as it is (it checks UTF-8 itself)
_UTF8 = {"utf_8"}
# codecs that are no character encoding of a file: escapes and transforms
_NOT_FILE_ENCODINGS = {"unicode_escape", "raw_unicode_escape", "idna", "punycode", "undefined"}


def as_utf8(data: bytes | bytearray, where: str | Path) -> bytes | bytearray:
    """`data` (modelDescription.xml of the archive `where`) as UTF-8; FMUFileError naming the
    file, the encoding and the offset of the first byte invalid in it."""
    name = _declared(data, where)
    if name is None:
        return data
    try:
        text = bytes(data).decode(name)
    except UnicodeDecodeError as error:
        bad = data[error.start:error.end].hex(" ")
        raise FMUFileError(f"{where}: modelDescription.xml: byte(s) {bad} at offset "
                           f"{error.start} are not valid {name.upper()}, the encoding the file "
                           "declares") from error
    # the decoded declaration names the old encoding: it now says what the bytes are
    return _DECLARED_TEXT.sub(r"\1\2UTF-8\2", text.lstrip("\ufeff"), count=1).encode()


def _declared(data: bytes | bytearray, where: str | Path) -> str | None:
    """The codec to decode `data` with; None when the engine reads it as it is (UTF-8)."""
    head = bytes(data[:4])
    for mark, codec in _MARKS:
        if head.startswith(mark):
            return None if codec == "utf-8" else codec
    found = _DECLARATION.match(bytes(data[:1024]).lstrip())
    if found is None:
        return None  # no declaration: UTF-8
    name = found.group(2).decode("ascii")
    try:
        info = codecs.lookup(name)
    except LookupError:
        raise FMUFileError(f"{where}: modelDescription.xml: its XML declaration names the "
                           f"encoding {name!r}, which Python does not know") from None
    if info.name.replace("-", "_") in _NOT_FILE_ENCODINGS \
            or not getattr(info, "_is_text_encoding", True):
        raise FMUFileError(f"{where}: modelDescription.xml: its XML declaration names "
                           f"{name!r}, which is not a character encoding")
    return None if info.name.replace("-", "_") in _UTF8 else name
