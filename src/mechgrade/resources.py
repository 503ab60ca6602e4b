"""Find the data mechgrade ships: ``templates/``, ``problems/`` and ``examples/``.

In a wheel they are package data inside ``mechgrade/``; in a source checkout (editable
install or ``PYTHONPATH=src``) they are the top-level folders of the repository.

>>> (shipped_dir("templates") / "feedback.html.j2").name
'feedback.html.j2'
"""

from __future__ import annotations

from pathlib import Path

_PACKAGE = Path(__file__).resolve().parent
_CHECKOUT = _PACKAGE.parent.parent


def shipped_dir(name: str) -> Path:
    """The folder ``name`` (``templates``, ``problems`` or ``examples``) that ships with mechgrade."""
    packaged = _PACKAGE / name
    if packaged.is_dir():
        return packaged
    return _CHECKOUT / name
