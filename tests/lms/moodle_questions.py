"""Moodle's XML question import and numerical grading, for the tests.

Followed from moodle/moodle ``question/format/xml/format.php`` (``readquestions``,
``import_question``, ``import_headers``, ``import_numerical``, ``import_calculated``,
``import_essay``): the file must parse as XML with a ``quiz`` root; each ``question``'s
``type`` picks the importer; ``import_calculated`` reads, without defaults (PHP would fail on a
missing index), every answer's ``tolerance``, ``tolerancetype``, ``correctanswerformat`` and
``correctanswerlength``, and every dataset definition's ``status``, ``name``, ``type``,
``distribution``, ``minimum``, ``maximum``, ``decimals``, ``itemcount`` and its
``dataset_item`` numbers and values; ``import_numerical`` reads ``tolerance`` (default 0) and
the units (``multiplier``, ``unit_name``).

Grading follows ``qtype_numerical_answer::get_tolerance_interval`` (``question/type/
numerical/question.php``, from its documented behaviour, not in the index): tolerance type 1
(relative) is ``tolerance * |answer|`` on each side, 2 (nominal) the tolerance itself; a
calculated question's answer formula is evaluated with the values of one dataset item, the
same item number for every wildcard of the question.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

WILDCARD = re.compile(r"\{([A-Za-z][^>} <`{\"']*)\}")  # qtype_calculated find_dataset_names


class MoodleImportError(Exception):
    """The import fails for this file (Moodle shows an error and imports nothing)."""


@dataclass
class MoodleQuestion:
    qtype: str
    name: str
    text: str
    defaultmark: float
    answers: list[dict] = field(default_factory=list)
    units: list[tuple[float, str]] = field(default_factory=list)
    datasets: dict[str, dict[int, float]] = field(default_factory=dict)


def _path(node: ET.Element | None, path: str, what: str) -> str:
    found = node.find(path) if node is not None else None
    if found is None:
        raise MoodleImportError(f"missing {what} ({path})")
    return (found.text or "").strip()


def read_quiz(text: str) -> list[MoodleQuestion]:
    """The questions Moodle imports from ``text``."""
    try:
        root = ET.fromstring(text)
    except ET.ParseError as err:
        raise MoodleImportError(f"not XML: {err}") from None
    if root.tag != "quiz":
        raise MoodleImportError(f"expected a <quiz>, found <{root.tag}>")
    out = []
    for question in root.findall("question"):
        kind = question.get("type")
        if kind == "category":
            _path(question, "category/text", "the category")
            continue
        if kind not in ("numerical", "calculated", "essay"):
            raise MoodleImportError(f"unexpected question type {kind!r}")
        q = MoodleQuestion(kind, _path(question, "name/text", "a name"),
                           _path(question, "questiontext/text", "the question text"),
                           float(question.findtext("defaultgrade", "1")))
        if kind == "essay":
            out.append(q)
            continue
        for answer in question.findall("answer"):
            entry = {"text": _path(answer, "text", "an answer's text"),
                     "fraction": float(answer.get("fraction", "0")) / 100}
            if kind == "numerical":
                entry["tolerance"] = float(answer.findtext("tolerance", "0"))
                entry["tolerancetype"] = 2
            else:
                entry["tolerance"] = float(_path(answer, "tolerance", "tolerance"))
                entry["tolerancetype"] = int(_path(answer, "tolerancetype", "tolerancetype"))
                entry["correctanswerformat"] = int(_path(answer, "correctanswerformat", "a "
                                                                                        "format"))
                entry["correctanswerlength"] = int(_path(answer, "correctanswerlength", "a "
                                                                                        "length"))
            q.answers.append(entry)
        for unit in question.findall("units/unit"):
            q.units.append((float(_path(unit, "multiplier", "a multiplier")),
                            _path(unit, "unit_name", "a unit name")))
        if kind == "calculated":
            for definition in question.findall("dataset_definitions/dataset_definition"):
                for part in ("status/text", "name/text", "type", "distribution/text",
                             "minimum/text", "maximum/text", "decimals/text", "itemcount"):
                    _path(definition, part, f"a dataset's {part}")
                name = _path(definition, "name/text", "a dataset's name")
                q.datasets[name] = {int(_path(i, "number", "an item number")):
                                    float(_path(i, "value", "an item value"))
                                    for i in definition.findall("dataset_items/dataset_item")}
            for answer in q.answers:
                for wildcard in WILDCARD.findall(answer["text"]):
                    if wildcard not in q.datasets:
                        raise MoodleImportError(f"no dataset for the wildcard {{{wildcard}}}")
        out.append(q)
    return out


def answer_for(question: MoodleQuestion, item: int | None = None) -> float:
    """The correct answer of ``question`` (for dataset item ``item``)."""
    (answer,) = [a for a in question.answers if a["fraction"] == 1.0]
    if question.qtype == "numerical":
        return float(answer["text"])
    formula = WILDCARD.sub(lambda m: repr(question.datasets[m[1]][item]), answer["text"])
    assert re.fullmatch(r"[-+0-9.eE() ]+", formula), formula
    return float(formula)


def moodle_accepts(question: MoodleQuestion, response: float, item: int | None = None) -> bool:
    """Whether Moodle marks ``response`` (in the question's first unit) right."""
    (answer,) = [a for a in question.answers if a["fraction"] == 1.0]
    value = answer_for(question, item)
    width = abs(value) * answer["tolerance"] if answer["tolerancetype"] == 1 \
        else answer["tolerance"]
    return value - width <= response <= value + width
