"""SSP (System Structure and Parameterization): systems read from .ssp archives and .ssd files
(SSP 1.0, and SSP 2.0 files as far as they use SSP 1.0 constructs), and written back as SSP 1.0
with System.to_ssp."""

from ..ssp_format.errors import SSPError, SSPWarning
from ..ssp_format.experiment import Experiment
from ..ssp_format.writer import write_ssp
from .load import Imported, load, read

__all__ = ["Experiment", "Imported", "SSPError", "SSPWarning", "load", "read", "write_ssp"]
