"""The one place the command line prints: every line made visible, never obeyed."""

from __future__ import annotations

import ast
from pathlib import Path

import click
from click.testing import CliRunner

from mechgrade.cli.common import say

CLI = Path(__file__).resolve().parents[2] / "src" / "mechgrade" / "cli"


def test_say_escapes_terminal_sequences_line_by_line():
    @click.command()
    def shout():
        say("ana\x1b]0;owned\x07\nbo\x1b[2J\x1b[8mhidden\rcy\u202e", err=True)

    result = CliRunner().invoke(shout)
    assert result.stderr == "ana\\x1b]0;owned\\x07\nbo\\x1b[2J\\x1b[8mhidden\\rcy\\u202e\n"


def test_every_command_prints_through_say():
    """No other module of the command line writes to the terminal itself."""
    printing = []
    for path in sorted(CLI.glob("*.py")):
        if path.name == "common.py":
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Call):
                func = node.func
                name = func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")
                if name in ("echo", "secho", "print", "write"):
                    printing.append(f"{path.name}:{node.lineno}: {ast.unparse(func)}")
    assert printing == []


CHATTY = """
import click
from mechgrade.cli.common import reports_errors, say

@click.command()
@reports_errors
def chatty():
    for n in range(200_000):
        say(f"line {n}")

chatty()
"""


def test_a_reader_that_stops_reading_ends_the_command_quietly_with_sigpipes_status():
    """``mechgrade solve ... | head``: the closed pipe is the reader's choice, not a fault of
    mechgrade's (no "internal error", nothing printed at exit), and the status is a shell's."""
    import subprocess
    import sys

    from mechgrade.cli.common import CLOSED_PIPE_EXIT

    process = subprocess.Popen([sys.executable, "-c", CHATTY], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE)
    assert process.stdout.readline() == b"line 0\n"
    process.stdout.close()
    _, stderr = process.communicate(timeout=60)
    assert (process.returncode, stderr) == (CLOSED_PIPE_EXIT, b"")


def test_a_closed_pipe_is_not_reported_as_an_internal_error():
    from mechgrade.cli.common import CLOSED_PIPE_EXIT, reports_errors

    @click.command()
    @reports_errors
    def cut():
        raise BrokenPipeError(32, "Broken pipe")

    result = CliRunner().invoke(cut)
    assert (result.exit_code, result.output) == (CLOSED_PIPE_EXIT, "")
