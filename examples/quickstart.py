"""The SysSimX quickstart: a linear source feeding an integrator, unchanged.

Prints the integrator's output at t = 5 s: 12.25 (forward Euler of y' = t, dt 0.1).

    python examples/quickstart.py
"""

from syssimx import Connection, CoSimComponent, PortSpec, PortType, System


class LinearSource(CoSimComponent):
    def __init__(self, name: str, a: float = 1.0, b: float = 0.0):
        super().__init__(name, group="Source")
        self.a = a
        self.b = b
        self.output_specs.update({
            "y": PortSpec(name="y", type=PortType.REAL, direction="out")
        })

    def _initialize_component(self, t0: float) -> None:
        pass

    def _do_step_internal(self, t: float, dt: float) -> None:
        pass

    def _update_output_states(self, t: float | None = None, event_names=None):
        t_now = 0.0 if t is None else t
        self.outputs["y"].set(self.a * t_now + self.b, t)


class Integrator(CoSimComponent):
    def __init__(self, name: str, x0: float = 0.0):
        super().__init__(name, group="Integrator")
        self.x0 = x0
        self.input_specs.update({
            "u": PortSpec(name="u", type=PortType.REAL, direction="in")
        })
        self.output_specs.update({
            "y": PortSpec(name="y", type=PortType.REAL, direction="out")
        })

    def _initialize_component(self, t0: float) -> None:
        self.x = self.x0
        self.outputs["y"].set(self.x, t0)

    def _do_step_internal(self, t: float, dt: float) -> None:
        u = self.inputs["u"].get()
        self.x = self.x + dt * float(u)

    def _update_output_states(self, t: float | None = None, event_names=None):
        self.outputs["y"].set(self.x, t)


if __name__ == "__main__":
    source = LinearSource(name="LinearSource", a=1.0, b=0.0)
    integrator = Integrator(name="Integrator", x0=0.0)

    system = System(name="QuickstartSystem")
    system.add_component(source)
    system.add_component(integrator)
    system.add_connection(Connection(
        src_comp="LinearSource", src_port="y",
        dst_comp="Integrator", dst_port="u",
    ))

    system.initialize(t0=0.0)
    result = system.run(t0=0.0, tf=5.0, dt=0.1)

    t_vals, data = result["Integrator"]
    print(t_vals[-1], data["y"][-1])
