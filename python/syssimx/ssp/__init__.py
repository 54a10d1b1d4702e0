"""SSP (System Structure and Parameterization): systems read from .ssp archives and .ssd files
(SSP 1.0, and SSP 2.0 files as far as they use SSP 1.0 constructs), and written back as SSP 1.0
with System.to_ssp."""

from .errors import SSPError, SSPWarning
from .experiment import Experiment
from .load import Imported, load, read
from .writer import write_ssp

__all__ = ["Experiment", "Imported", "SSPError", "SSPWarning", "load", "read", "write_ssp"]
