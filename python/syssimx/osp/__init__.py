"""OSP system structures (the Open Simulation Platform's OspSystemStructure.xml, as libcosim
and its `cosim` tool read them): the same System the other front-ends build."""

from .errors import OSPError, OSPWarning
from .load import OSPImported, load, read

__all__ = ["OSPError", "OSPImported", "OSPWarning", "load", "read"]
