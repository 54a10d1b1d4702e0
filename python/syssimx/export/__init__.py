"""A System exported as one Co-Simulation FMU (FMI 2.0 or 3.0) whose binary is the engine: the
plan and the member FMUs travel in its resources, and its events are located inside doStep."""

from .api import export_fmu

__all__ = ["export_fmu"]
