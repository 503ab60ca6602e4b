"""Starting specs for instructors: commented templates that pass ``mechgrade check`` as written.

Each template (``templates/new/<name>.yaml.j2``) teaches the spec by its comments and carries
``expect:`` answers worked out by hand for its own numbers.

>>> text = starter_spec("hw1_p1", "particle", schema_ref="problem.schema.json")
>>> text.splitlines()[0]
'# yaml-language-server: $schema=problem.schema.json'
>>> [line for line in text.splitlines() if line.startswith("id:")]
['id: hw1_p1                     # must equal the file name without .yaml']
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import jinja2

from ..errors import Location, OutputError, SpecError
from ..files import clean_text
from ..resources import shipped_dir
from .load import SCHEMA_PATH, problem_schema

TEMPLATES = ("particle", "rotating-frame", "rolling", "linkage", "rigid-body",
             "incline-friction", "pin-body", "rolling-body", "impact", "vibration")
"""The starting specs, simplest first: kinematics, then kinetics."""


def check_problem_id(problem_id: str) -> str:
    """``problem_id`` if it is a valid problem id (the schema's identifier rule), else a
    :class:`SpecError` saying why.

    >>> check_problem_id("hw3_p1")
    'hw3_p1'
    >>> check_problem_id("hw3.p1")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechgrade.errors.SpecError: ID: expected letters, digits and '_' ... found 'hw3.p1'
    """
    pattern = problem_schema()["$defs"]["identifier"]["pattern"]
    if not re.fullmatch(pattern, problem_id):
        raise SpecError("expected letters, digits and '_' starting with a letter (the id is the "
                        "file name and answers are named problem_id.objective_id), found "
                        f"{problem_id!r}", where=Location(field="ID"))
    return problem_id


def starter_spec(problem_id: str, template: str, *, schema_ref: str) -> str:
    """The text of a starting spec for ``problem_id`` from ``template`` (one of
    :data:`TEMPLATES`), whose first line points editors at the schema ``schema_ref``."""
    if template not in TEMPLATES:
        raise SpecError(f"expected a template among {', '.join(TEMPLATES)}, found {template!r}",
                        where=Location(field="--template"))
    env = jinja2.Environment(loader=jinja2.FileSystemLoader(shipped_dir("templates") / "new"),
                             undefined=jinja2.StrictUndefined, keep_trailing_newline=True,
                             autoescape=False)
    modeline = f"# yaml-language-server: $schema={schema_ref}"
    return env.get_template(f"{template}.yaml.j2").render(
        id=check_problem_id(problem_id), modeline=modeline)


def schema_reference(folder: str | os.PathLike) -> str:
    """How a file in ``folder`` names the shipped schema: a relative path where there is one
    (the repository's problems/ use ``../src/mechgrade/spec/problem.schema.json``), else its URI.

    >>> schema_reference(SCHEMA_PATH.parent)
    'problem.schema.json'
    """
    try:
        return Path(os.path.relpath(SCHEMA_PATH, Path(folder).resolve())).as_posix()
    except ValueError:  # another drive on Windows: no relative path exists
        return SCHEMA_PATH.as_uri()


def write_starter(problem_id: str, template: str, folder: str | os.PathLike = ".") -> Path:
    """Write ``<folder>/<problem_id>.yaml`` from ``template``; never overwrites a file.

    >>> import tempfile
    >>> folder = tempfile.mkdtemp()
    >>> write_starter("p1", "rolling", folder).name
    'p1.yaml'
    >>> write_starter("p1", "rolling", folder)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechgrade.errors.OutputError: .../p1.yaml: expected a new file, found an existing one; ...
    """
    folder = Path(folder)
    target = folder / f"{check_problem_id(problem_id)}.yaml"
    if not folder.is_dir():
        raise OutputError("expected an existing folder to write the spec into, found none",
                          where=Location(str(folder)))
    text = clean_text(starter_spec(problem_id, template, schema_ref=schema_reference(folder)))
    try:
        with open(target, "x", encoding="utf-8", newline="\n") as handle:
            handle.write(text)
    except FileExistsError:
        raise OutputError("expected a new file, found an existing one; choose another ID or "
                          "--out folder (new never overwrites)",
                          where=Location(str(target))) from None
    except OSError as err:
        raise OutputError(f"cannot write the file ({err.strerror or err})",
                          where=Location(str(target))) from None
    return target
