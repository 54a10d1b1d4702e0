"""Structure of a system: data-flow analysis and the text report."""

from .analysis import (
    SystemAnalysis,
    analyze,
    analyze_system,
    feedthrough_from_model_description,
)
from .describe import describe_system

__all__ = [
    "SystemAnalysis",
    "analyze",
    "analyze_system",
    "describe_system",
    "feedthrough_from_model_description",
]
