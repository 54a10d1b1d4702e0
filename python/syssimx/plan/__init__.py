"""A system's plan: the text of format `syssimx-plan 1` (docs/reference/plan-format.md) that the
engine builds a system from, with no Python where the system holds none."""
