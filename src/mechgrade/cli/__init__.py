"""The ``mechgrade`` command line: thin click commands over the library.

Only this package prints or exits. Every :class:`~mechgrade.errors.MechgradeError` becomes one
message on stderr and exit code 2; nothing imports this package. A command's module is imported
only when that command is used (see :class:`~mechgrade.cli.common.LazyGroup`).
"""

from __future__ import annotations

from .common import main

__all__ = ["main"]
