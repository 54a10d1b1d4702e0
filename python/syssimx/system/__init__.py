"""Systems of components: connections, algorithms, results (each imported on first use)."""

from .._lazy import lazy_names

_MODULES = {
    "ConfigError": ".loader",
    "Connection": ".connection",
    "EventConnection": ".connection",
    "EventRecord": ".event_record",
    "GaussSeidelAlgorithm": ".algorithms",
    "HybridAlgorithm": ".algorithms",
    "IJCSAAlgorithm": ".algorithms",
    "JacobiAlgorithm": ".algorithms",
    "LocalizationTrial": ".event_record",
    "MemberRuns": ".member_runs",
    "SimulationResult": ".results",
    "Statistics": ".results",
    "StepControl": ".algorithms",
    "System": ".system",
    "SystemHistory": ".system_history",
    "SystemState": ".saved_state",
    "Termination": ".termination",
    "build_system": ".loader",
    "load_config": ".loader",
    "run_from_config": ".loader",
}

__all__ = list(_MODULES)

__getattr__, __dir__ = lazy_names(__name__, _MODULES)
