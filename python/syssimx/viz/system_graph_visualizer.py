"""A picture of a system: components clustered by group, their ports, data and event edges.

Data edges are labelled with their units; edges of an algebraic loop are drawn bold in the loop
colour; event connections are dashed in the event colour. Rendering needs Graphviz's ``dot``.
"""

from __future__ import annotations

from html import escape
from pathlib import Path
from typing import Any

from ..extras import require
from ..graph.analysis import SystemAnalysis, analyze_system
from ..graph.ports import connection_unit_label, port_kind, port_label

DATA_COLOR = "#4d4d4d"
LOOP_COLOR = "#c0392b"
EVENT_COLOR = "#e67e22"
GROUP_FILLS = ("#eaf2fb", "#eafaf1", "#fdf2e9", "#f4ecf7", "#fef9e7", "#ebedef")
graphviz = require("graphviz", "drawing a system (SystemGraphVisualizer, System._repr_svg_)")

LEGEND = "data: solid, with units    event: dashed, orange    algebraic loop: bold, red"


class SystemGraphVisualizer:
    """Draws ``system`` with Graphviz.

    The system needs ``components`` (name -> component with ``group``, ``input_specs``,
    ``output_specs``), ``connections`` and ``event_connections`` (with ``src_comp``,
    ``src_port``, ``dst_comp``, ``dst_port``).
    """

    def __init__(self, system: Any) -> None:
        self.system = system

    def graph(self) -> graphviz.Digraph:
        """The Graphviz description of the system (not rendered)."""
        return _SystemDrawing(self.system, analyze_system(self.system)).draw()

    def visualize(self, filename: str | Path | None = None, format: str = "svg"
                  ) -> graphviz.Digraph:
        """Build the picture; with ``filename``, also write it as SysSimX does: a suffix of
        ``filename`` is dropped, the picture goes to ``<stem>.<format>`` and the Graphviz source
        to ``<stem>`` (``visualize("out/graph.svg")`` writes out/graph.svg and out/graph).

        The returned object shows itself in Jupyter.
        """
        drawing = self.graph()
        if filename is not None:
            stem = Path(filename)
            _render(drawing, stem.with_suffix("") if stem.suffix else stem, format,
                    keep_source=True)
        return drawing

    def save(self, path: str | Path) -> Path:
        """Write the picture to ``path``; the suffix picks the format (.svg, .png, .pdf, .gv)."""
        target = Path(path)
        drawing = self.graph()
        suffix = target.suffix.lstrip(".").lower()
        if not suffix:
            raise ValueError(f"cannot tell the picture format from {str(target)!r}: add a suffix")
        from ..atomic_file import atomic_path

        with atomic_path(target) as temporary:
            if suffix in ("gv", "dot"):
                temporary.write_text(drawing.source)
            else:
                _render(drawing, temporary.with_suffix(""), suffix)
        return target


def system_svg(system: Any) -> str:
    """The system's picture as SVG text (what ``System._repr_svg_`` shows in Jupyter)."""
    drawing = SystemGraphVisualizer(system).graph()
    try:
        return drawing.pipe(format="svg", encoding="utf-8")
    except graphviz.ExecutableNotFound as error:
        raise RuntimeError(_NO_DOT) from error
    except graphviz.CalledProcessError as error:  # a RuntimeError, which a display catches
        raise RuntimeError(f"Graphviz's dot could not draw {getattr(system, 'name', '')!r}: "
                           f"{error.stderr}") from error


_NO_DOT = "drawing a system needs Graphviz's 'dot' program on PATH (e.g. apt install graphviz)"


def _render(drawing: graphviz.Digraph, stem: Path, format: str, keep_source: bool = False
            ) -> Path:
    try:
        rendered = drawing.render(filename=stem.name, directory=stem.parent or ".",
                                  format=format, cleanup=not keep_source)
    except graphviz.ExecutableNotFound as error:
        raise RuntimeError(_NO_DOT) from error
    return Path(rendered)


def _literal(text: str) -> str:
    """A name as a DOT attribute's text, shown as it is: a backslash is no escape (a trailing
    one would swallow the closing quote) and "<...>" no HTML label."""
    return graphviz.escape(text)


class _SystemDrawing:
    """One drawing pass: node ids are positional, so any component or port name is safe."""

    def __init__(self, system: Any, analysis: SystemAnalysis) -> None:
        self.system = system
        self.analysis = analysis
        self.components: dict[str, Any] = dict(system.components)
        self.node_ids = {name: f"c{i}" for i, name in enumerate(self.components)}
        self.port_ids: dict[tuple[str, str, str], str] = {}
        for name, component in self.components.items():
            for i, port in enumerate(component.input_specs):
                self.port_ids[(name, "in", port)] = f"i{i}"
            for i, port in enumerate(component.output_specs):
                self.port_ids[(name, "out", port)] = f"o{i}"
        self.generation_of = {
            name: index
            for index, generation in enumerate(analysis.generations, start=1)
            for name in generation
        }
        self.loop_members = {name for loop in analysis.loops for name in loop}

    def draw(self) -> graphviz.Digraph:
        title = str(getattr(self.system, "name", "") or "system")
        drawing = graphviz.Digraph(name=_literal(title))
        drawing.attr(rankdir="LR", fontname="Helvetica", labelloc="t",
                     label=_literal(f"{title}\n{LEGEND}"), fontsize="11")
        drawing.attr("node", shape="plaintext", fontname="Helvetica", fontsize="10")
        drawing.attr("edge", fontname="Helvetica", fontsize="9", color=DATA_COLOR)
        self._add_components(drawing)
        self._add_data_edges(drawing)
        self._add_event_edges(drawing)
        return drawing

    def _add_components(self, drawing: graphviz.Digraph) -> None:
        groups: dict[str, list[str]] = {}
        for name, component in self.components.items():
            group = getattr(component, "group", None)
            if group:
                groups.setdefault(str(group), []).append(name)
            else:
                self._add_component(drawing, name, fill="#ffffff")
        for index, (group, members) in enumerate(groups.items()):
            fill = GROUP_FILLS[index % len(GROUP_FILLS)]
            with drawing.subgraph(name=f"cluster_{index}") as cluster:
                cluster.attr(label=_literal(group), style="rounded,filled", fillcolor=fill,
                             color="#a0a0a0", id=_literal(f"group:{group}"))
                for name in members:
                    self._add_component(cluster, name, fill="#ffffff")

    def _add_component(self, drawing: graphviz.Digraph, name: str, fill: str) -> None:
        component = self.components[name]
        inputs = list(component.input_specs.values())
        outputs = list(component.output_specs.values())
        border = LOOP_COLOR if name in self.loop_members else DATA_COLOR
        generation = self.generation_of.get(name)
        header = f"<B>{escape(name)}</B>"
        if generation is not None:
            header += f'<BR/><FONT POINT-SIZE="8">generation {generation}</FONT>'
        rows = [f'<TR><TD COLSPAN="2" BGCOLOR="#d9d9d9">{header}</TD></TR>']
        for row in range(max(len(inputs), len(outputs), 1)):
            left = self._port_cell(name, "in", inputs[row] if row < len(inputs) else None)
            right = self._port_cell(name, "out", outputs[row] if row < len(outputs) else None)
            rows.append(f"<TR>{left}{right}</TR>")
        label = (
            f'<<TABLE BORDER="1" CELLBORDER="0" CELLSPACING="0" CELLPADDING="3" '
            f'COLOR="{border}" BGCOLOR="{fill}">{"".join(rows)}</TABLE>>'
        )
        drawing.node(self.node_ids[name], label=label, id=_literal(f"component:{name}"),
                     tooltip=_literal(name))

    def _port_cell(self, component: str, direction: str, spec: Any) -> str:
        align = "LEFT" if direction == "in" else "RIGHT"
        if spec is None:
            return f'<TD ALIGN="{align}"> </TD>'
        port = self.port_ids[(component, direction, spec.name)]
        color = EVENT_COLOR if port_kind(spec) == "event" else "#000000"
        text = escape(port_label(spec))
        return f'<TD PORT="{port}" ALIGN="{align}"><FONT COLOR="{color}">{text}</FONT></TD>'

    def _endpoint(self, component: str, direction: str, port: str) -> str:
        node = self.node_ids[component]
        port_id = self.port_ids.get((component, direction, port))
        if port_id is None:
            return node
        return f"{node}:{port_id}:{'e' if direction == 'out' else 'w'}"

    def _add_data_edges(self, drawing: graphviz.Digraph) -> None:
        in_loop = set(self.analysis.loop_connections)
        for c in self.system.connections:
            key = (c.src_comp, c.src_port, c.dst_comp, c.dst_port)
            src_spec = self.components[c.src_comp].output_specs.get(c.src_port)
            dst_spec = self.components[c.dst_comp].input_specs.get(c.dst_port)
            attributes = {
                "id": _literal(f"connection:{c.src_comp}.{c.src_port}->{c.dst_comp}."
                               f"{c.dst_port}"),
                "class": "loop" if key in in_loop else "data",
                "label": connection_unit_label(src_spec, dst_spec) or "",
            }
            if key in in_loop:
                attributes.update(color=LOOP_COLOR, fontcolor=LOOP_COLOR, penwidth="2.5")
            drawing.edge(self._endpoint(c.src_comp, "out", c.src_port),
                         self._endpoint(c.dst_comp, "in", c.dst_port), **attributes)

    def _add_event_edges(self, drawing: graphviz.Digraph) -> None:
        for c in getattr(self.system, "event_connections", []):
            drawing.edge(
                self._endpoint(c.src_comp, "out", c.src_port),
                self._endpoint(c.dst_comp, "in", c.dst_port),
                id=_literal(f"event:{c.src_comp}.{c.src_port}->{c.dst_comp}.{c.dst_port}"),
                **{"class": "event"},
                color=EVENT_COLOR,
                fontcolor=EVENT_COLOR,
                style="dashed",
                label="event",
            )
