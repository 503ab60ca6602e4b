"""The ``mechgrade`` command line: thin click commands over the library.

Only this package prints or exits. Every :class:`~mechgrade.errors.MechgradeError` becomes one
message on stderr and exit code 2; nothing imports this package.
"""

from __future__ import annotations


from .common import main
from . import solve as _solve  # noqa: F401  (registers its command)
from . import check as _check  # noqa: F401
from . import export as _export  # noqa: F401
from . import grade as _grade  # noqa: F401
from . import gradescope as _gradescope  # noqa: F401
from . import schema as _schema  # noqa: F401
from . import new as _new  # noqa: F401
from . import handout as _handout  # noqa: F401

__all__ = ["main"]
