"""The `cli-reference` directive: the command line's reference, generated from its argument
parser (`syssimx.cli.build_parser`), one section per command with argparse's own help text.
Nothing is written twice: a new option appears here when it is added to the parser."""

from __future__ import annotations

import argparse
import os
from typing import Any

from docutils import nodes
from sphinx.application import Sphinx
from sphinx.util.docutils import SphinxDirective


def _commands(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    """The subcommands' parsers by name, in the order they were added."""
    for action in parser._actions:  # argparse offers no public walk of its subparsers
        if isinstance(action, argparse._SubParsersAction):
            return dict(action.choices.items())
    return {}


def _help(parser: argparse.ArgumentParser) -> str:
    """argparse's help at a fixed width (it follows the terminal's otherwise)."""
    saved = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = "78"
    try:
        return parser.format_help()
    finally:
        if saved is None:
            del os.environ["COLUMNS"]
        else:
            os.environ["COLUMNS"] = saved


class CliReference(SphinxDirective):
    has_content = False

    def _section(self, title: str, parser: argparse.ArgumentParser, summary: str) -> Any:
        section = nodes.section(ids=[nodes.make_id(f"cli {title}")], names=[title])
        section += nodes.title(text=title)
        if summary:
            section += nodes.paragraph(text=summary)
        help_text = _help(parser)
        block = nodes.literal_block(help_text, help_text, language="text")
        section += block
        self.state.document.note_implicit_target(section, section)
        return section

    def run(self) -> list[nodes.Node]:
        from syssimx.cli import build_parser

        parser = build_parser()
        sections = [self._section("syssimx", parser, parser.description or "")]
        helps = {}
        for action in parser._actions:
            if isinstance(action, argparse._SubParsersAction):
                helps = {choice.dest: choice.help for choice in action._choices_actions}
        for name, command in _commands(parser).items():
            sections.append(self._section(f"syssimx {name}", command, helps.get(name) or ""))
        return sections


def setup(app: Sphinx) -> dict[str, Any]:
    app.add_directive("cli-reference", CliReference)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
