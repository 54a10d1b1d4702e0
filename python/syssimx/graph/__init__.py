"""Structure of a system: data-flow analysis and the text report (each imported on first use)."""

from .._lazy import lazy_names

_MODULES = {
    "SystemAnalysis": ".analysis",
    "analyze": ".analysis",
    "analyze_system": ".analysis",
    "describe_system": ".describe",
    "feedthrough_from_model_description": ".analysis",
}

__all__ = list(_MODULES)

__getattr__, __dir__ = lazy_names(__name__, _MODULES)
