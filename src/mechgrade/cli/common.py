"""The command group and the one place where library errors turn into exit codes."""

from __future__ import annotations

import functools

import click

from .. import __version__
from ..errors import MechgradeError


INTERNAL_ERROR_EXIT = 3
"""The run finished and wrote its outputs, but mechgrade itself failed on some students or
answers (they are ``not_evaluated``; the summary lists where). Bad input exits with 2."""


class UserFailure(click.ClickException):
    """A bad-input failure: the library's message alone, exit code 2."""

    exit_code = 2

    def show(self, file=None) -> None:  # noqa: D102 - click's hook
        click.echo(self.format_message(), err=True)


def reports_errors(command):
    """Run a command body, turning :class:`MechgradeError` into one message and exit code 2."""

    @functools.wraps(command)
    def wrapper(*args, **kwargs):
        try:
            return command(*args, **kwargs)
        except MechgradeError as err:
            raise UserFailure(str(err)) from None

    return wrapper


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="mechgrade")
def main() -> None:
    """Check and grade engineering dynamics homework against a model-driven reference solver."""
