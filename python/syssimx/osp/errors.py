"""What reading an OSP system structure raises and warns."""

from __future__ import annotations

from ..errors import ConfigurationError


class OSPError(ConfigurationError):
    """An OSP system structure cannot be used: names the file and the element that is wrong."""


class OSPWarning(UserWarning):
    """Something in an OSP system structure that syssimx leaves out, named."""
