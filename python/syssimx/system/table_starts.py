"""Table sources' values at t0, handed to the inputs they drive before anything initializes."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from ..bridge.plan import EnginePlan, typed
from ..components.base import CoSimComponent
from ..units import conversion
from .connection import Connection


def start_tables(components: Mapping[str, CoSimComponent], connections: Sequence[Connection],
                 plan: EnginePlan, t0: float) -> None:
    """Before any component initializes: each table's outputs at t0, and every input a table
    drives starting at that value, so an FMU has it before it leaves initialization mode (as
    FMPy sets its inputs)."""
    if not plan.tables:
        return
    starts = {name: plan.start_table(components[name], t0) for name in plan.tables}
    for connection in connections:
        if connection.src_comp not in starts:
            continue
        value = starts[connection.src_comp][connection.src_port]
        source, target = components[connection.src_comp], components[connection.dst_comp]
        spec = target.input_specs[connection.dst_port]
        scale, offset = conversion(source.output_specs[connection.src_port].unit, spec.unit)
        target.set_inputs({connection.dst_port: typed(spec.type, scale * value + offset)})
