"""SSP (System Structure and Parameterization 1.0): systems read from .ssp archives and .ssd
files, and written back with System.to_ssp."""

from .errors import SSPError, SSPWarning
from .experiment import Experiment
from .load import Imported, load, read
from .writer import write_ssp

__all__ = ["Experiment", "Imported", "SSPError", "SSPWarning", "load", "read", "write_ssp"]
