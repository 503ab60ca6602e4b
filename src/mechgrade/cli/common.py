"""The command group, the one place where library errors turn into exit codes, and the one
place where anything is printed (:func:`say`)."""

from __future__ import annotations

import functools
import importlib
import os
import sys
from pathlib import Path
from typing import TYPE_CHECKING

import click

from .. import __version__
from ..errors import MechgradeError, brief_exception
from ..files import visible_text

if TYPE_CHECKING:
    from ..outfolder import Committed


CLOSED_PIPE_EXIT = 141
"""The reader of the output went away (``mechgrade solve ... | head``): the exit status a
shell gives a command that SIGPIPE stopped (128 + 13), without a message: it is not a fault."""

INTERNAL_ERROR_EXIT = 3
"""The run finished and wrote its outputs, but mechgrade itself failed on some students or
answers (they are ``not_evaluated``; the summary lists where). Bad input exits with 2."""


def say(text: str = "", *, err: bool = False, nl: bool = True) -> None:
    """Print ``text`` (on stderr with ``err``), each of its lines made visible
    (:func:`mechgrade.files.visible_text`): a name or answer holding a terminal control
    sequence (window title, clear screen, hidden text) is shown escaped, never obeyed.
    Every command prints through here."""
    click.echo("\n".join(map(visible_text, text.split("\n"))), err=err, nl=nl)


class UserFailure(click.ClickException):
    """A bad-input failure: the library's message alone, exit code 2."""

    exit_code = 2

    def show(self, file=None) -> None:  # noqa: D102 - click's hook
        say(self.format_message(), err=True)


class InternalFailure(click.ClickException):
    """A fault of mechgrade's: one line saying so, exit code 3 (``MECHGRADE_DEBUG=1`` shows the
    traceback instead)."""

    exit_code = INTERNAL_ERROR_EXIT

    def show(self, file=None) -> None:  # noqa: D102 - click's hook
        say(self.format_message(), err=True)


def reports_errors(command):
    """Run a command body, turning :class:`MechgradeError` into one message and exit code 2,
    and any other exception (a bug) into one line and exit code 3, never a traceback."""

    @functools.wraps(command)
    def wrapper(*args, **kwargs):
        try:
            return command(*args, **kwargs)
        except MechgradeError as err:
            raise UserFailure(str(err)) from None
        except (click.ClickException, click.exceptions.Exit, click.Abort, SystemExit,
                KeyboardInterrupt):
            raise
        except BrokenPipeError:
            _drop_stdout()
            raise SystemExit(CLOSED_PIPE_EXIT) from None
        except Exception as exc:  # noqa: BLE001 - the last boundary before the user
            if os.environ.get("MECHGRADE_DEBUG"):
                raise
            raise InternalFailure(f"internal error: {brief_exception(exc)}; please report it "
                                  f"with the command and files that caused it (set "
                                  f"MECHGRADE_DEBUG=1 for the traceback)") from None

    return wrapper


def _drop_stdout() -> None:
    """Point the standard output at the null device, so that the interpreter's flush at exit
    does not fail on the closed pipe again (as Python's signal documentation advises)."""
    try:
        descriptor = sys.stdout.fileno()
    except (AttributeError, OSError, ValueError):  # a test's captured output: nothing to drop
        return
    null = os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, descriptor)
    os.close(null)


MAX_LISTED = 50
"""Items of one list a summary shows; the rest are counted (every one is in the outputs)."""


def listed(title: str, items, where: str) -> list[str]:
    """A summary's list: its title line, then each item indented, at most :data:`MAX_LISTED`.

    >>> listed("Removed", ["a", "b"], "manifest.json")
    ['Removed:', '  a', '  b']
    """
    if not items:
        return []
    lines = [f"{title}:", *(f"  {item}" for item in items[:MAX_LISTED])]
    if len(items) > MAX_LISTED:
        lines.append(f"  ... and {len(items) - MAX_LISTED} more (all in {where})")
    return lines


def output_lines(done: Committed) -> list[str]:
    """What replacing the output folder did, for the summary: the previous run's files removed,
    the instructor's files kept, the leftovers of an interrupted run cleared."""
    return [*listed("Removed from the previous run (not written by this one)", done.removed,
                    "manifest.json"),
            *listed("Kept (not written by mechgrade)", done.kept, "manifest.json"),
            *listed("Before this run", done.notes, "manifest.json")]


def run_arguments() -> dict:
    """The running command's arguments, as its ``manifest.json`` records them (paths as given).
    """
    params = click.get_current_context().params
    return {name: str(value) if isinstance(value, os.PathLike) else
            list(value) if isinstance(value, tuple) else value
            for name, value in params.items()}


def run_inputs(*, assignment: Path | None = None, spec=None, results: Path | None = None,
               roster: Path | None = None, templates_dir: Path | None = None,
               template_names: tuple[str, ...] = ()) -> tuple[tuple[str, Path], ...]:
    """The ``(role, path)`` of every file a run read, for its ``manifest.json``: the assignment
    and its problems (``spec``), a results file, the roster, the templates used from
    ``templates_dir``."""
    found: list[tuple[str, Path]] = []
    if assignment is not None:
        found.append(("assignment", assignment))
    if spec is not None:
        found.extend(("problem", ref.path) for ref in spec.problems)
    if results is not None:
        found.append(("results", results))
    if roster is not None:
        found.append(("roster", roster))
    if templates_dir is not None:
        found.extend(("template", templates_dir / name) for name in template_names)
    return tuple(found)


def claim_out(out_dir, kind):
    """The claimed output folder of the running command (:func:`mechgrade.outfolder.claim`),
    released when the command ends, whichever way."""
    from ..outfolder import claim

    return click.get_current_context().with_resource(claim(out_dir, kind))


def warn_about_the_cache() -> None:
    """Print, once before a command solves anything, why the solver's disk cache is not used
    (a folder or key others may write or own); a cache setting that is not valid is an error
    (:class:`~mechgrade.errors.SettingError`, exit 2)."""
    from ..solve import cache

    message = cache.warning()
    if message:
        say(f"warning: {message}", err=True)


COMMANDS = {
    "catalog": ("catalog", "Write a browsable HTML catalogue of the problems in PATHS (files or "
                           "folders)."),
    "check": ("check", "Validate problem files (or folders of them) and run every expect: test."),
    "export": ("export", "Export RESULTS_JSON (written by 'mechgrade grade') for an LMS or a "
                         "spreadsheet."),
    "export-questions": ("questions", "Write ASSIGNMENT's objectives as quiz questions for "
                                      "Canvas (QTI) or Moodle (XML), each problem with its own "
                                      "verified variants."),
    "grade": ("grade", "Grade every submission in SUBMISSIONS_DIR against ASSIGNMENT."),
    "gradescope": ("gradescope", "Grade one Gradescope submission against ASSIGNMENT and write "
                                 "results.json."),
    "handout": ("handout", "Write every roster student's sheet for ASSIGNMENT, with their own "
                           "numbers, and givens.csv (every student's givens) for the instructor."),
    "new": ("new", "Write ID.yaml, a commented starting spec that passes `mechgrade check` as "
                   "written."),
    "report": ("report", "Write the class report of RESULTS_JSON as one self-contained HTML file."),
    "schema": ("schema", "Print the path of the problem-spec JSON Schema, or write a copy of it to "
                         "--out."),
    "solve": ("solve", "Solve PROBLEM_FILE and print each objective's reference answer."),
}
"""Every command: the module of :mod:`mechgrade.cli` that defines it, and its one-line help.

A command module is imported only when its command runs (or shows its own help): importing
sympy alone takes longer than click's whole start-up. ``tests/cli/test_startup.py`` checks that
each line is the command's own short help."""


class LazyGroup(click.Group):
    """A group that imports a command's module on first use (click's lazy-group pattern).

    The module registers its command with ``@main.command(...)`` as it is imported; the group's
    own help lists every command from :data:`COMMANDS` without importing any of them.
    """

    def __init__(self, *args, lazy: dict[str, tuple[str, str]], **kwargs) -> None:
        super().__init__(*args, **kwargs)
        self.lazy = lazy

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted({*self.commands, *self.lazy})

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        if cmd_name not in self.commands and cmd_name in self.lazy:
            importlib.import_module(f"{__package__}.{self.lazy[cmd_name][0]}")
        return self.commands.get(cmd_name)

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        names = self.list_commands(ctx)
        if not names:
            return
        limit = formatter.width - 6 - max(len(name) for name in names)
        rows = [(name, self.commands[name].get_short_help_str(limit) if name in self.commands
                 else click.Command(name, help=self.lazy[name][1]).get_short_help_str(limit))
                for name in names]
        with formatter.section("Commands"):
            formatter.write_dl(rows)


@click.group(cls=LazyGroup, lazy=COMMANDS,
             context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="mechgrade")
def main() -> None:
    """Check and grade engineering dynamics homework against a model-driven reference solver."""
