"""What reading an SSP raises and warns."""

from __future__ import annotations

from ..errors import ConfigurationError


class SSPError(ConfigurationError):
    """An SSP or SSD file cannot be used: names the file and the element that is wrong."""


class SSPWarning(UserWarning):
    """Something in an SSP that syssimx does not support and leaves out of the system."""
