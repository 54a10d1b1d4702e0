"""Variable names a NetCDF file can hold, for every reader: the format forbids '/' and control
characters, scipy reads names as Latin-1 where the format says UTF-8, so a name other than
plain ASCII is written percent-encoded (its UTF-8 bytes, as in a URL: "x/y" is "x%2Fy", "θ" is
"%CE%B8"), the name itself kept in the variable's `long_name` attribute."""

from __future__ import annotations

import string
from urllib.parse import quote

# printable ASCII that NetCDF allows in a name, '%' (the escape) aside
_KEPT = "".join(c for c in string.punctuation if c not in "/%")


def netcdf_name(name: str) -> str:
    """`name` as a NetCDF name every reader reads alike: itself when it is one already."""
    encoded = quote(name, safe=_KEPT)
    # the first character: a letter, a digit or '_'
    return encoded if encoded[:1].isalnum() or encoded[:1] == "_" else "_" + encoded
