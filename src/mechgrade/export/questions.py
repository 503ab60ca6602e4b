"""Questions out: a :class:`~mechgrade.grade.questions.QuestionBank` as Canvas QTI or Moodle XML.

:data:`QUESTION_WRITERS` is the explicit registry: format -> function
``(bank, out_path, options) -> notes``.

**Canvas** (``canvas-qti``): an IMS content package (``imsmanifest.xml`` and one QTI 1.2
assessment) laid out as Canvas's own QTI export writes it (canvas-lms ``lib/cc/qti/
qti_generator.rb``, ``qti_items.rb``): each number objective a ``calculated_question``
whose ``itemproc_extension/calculated`` holds the tolerance (``answer_tolerance``, ``1%`` or
an absolute number), the decimal places, the variables (``vars``, with their decimals as
``scale``) and one ``var_set`` per variant with its answer; each symbolic objective an
``essay_question``. The answers are the solver's, one per variant: no formula is written (a
dynamics answer has none), so the variants must not be regenerated in Canvas's editor.

**Moodle** (``moodle-xml``): a ``<quiz>`` as Moodle's XML format reads it
(``question/format/xml/format.php``, ``import_calculated``, ``import_numerical``,
``import_essay``): a problem drawn per student is a ``calculated`` question with one dataset
per variable and one for the answer (``{mg_answer}``), synchronised items; a problem without
variants a ``numerical`` question; each with its unit (and the SI unit, with its multiplier)
and tolerance (``tolerancetype`` 1 relative, 2 nominal); symbolic objectives ``essay``.
"""

from __future__ import annotations

import html
import io
import os
import re
import xml.etree.ElementTree as ET
import zipfile
from typing import Callable, Literal

from ..files import write_bytes, write_text
from ..grade.questions import EssayItem, NumberItem, QuestionBank, Variable
from ..grade.results import unit_text
from ..units import si_factor, si_unit

QTI_NAMESPACE = "http://www.imsglobal.org/xsd/ims_qtiasiv1p2"
QTI_SCHEMA = "http://www.imsglobal.org/xsd/ims_qtiasiv1p2p1.xsd"
MANIFEST_NAMESPACE = "http://www.imsglobal.org/xsd/imsccv1p1/imscp_v1p1"


def write_canvas_qti(bank: QuestionBank, out_path: str | os.PathLike) -> tuple[str, ...]:
    """Write the Canvas QTI package (a zip) of ``bank``; return notes for the user."""
    ident = _ident(bank.assignment_id)
    assessment = canvas_assessment(bank, ident)
    manifest = _manifest(ident)
    data = io.BytesIO()
    with zipfile.ZipFile(data, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("imsmanifest.xml", _xml_bytes(manifest))
        archive.writestr(f"{ident}/{ident}.xml", _xml_bytes(assessment))
    write_bytes(out_path, data.getvalue())
    return _notes(bank)


def write_moodle_xml(bank: QuestionBank, out_path: str | os.PathLike) -> tuple[str, ...]:
    """Write the Moodle XML file of ``bank``; return notes for the user."""
    write_text(out_path, _xml_bytes(moodle_quiz(bank)).decode("utf-8"))
    return _notes(bank)


QUESTION_WRITERS: dict[str, Callable[[QuestionBank, str | os.PathLike], tuple[str, ...]]] = {
    "canvas-qti": write_canvas_qti,
    "moodle-xml": write_moodle_xml,
}
DEFAULT_SUFFIX = {"canvas-qti": ".zip", "moodle-xml": ".xml"}


def _notes(bank: QuestionBank) -> tuple[str, ...]:
    notes = [f"{item.key}: {note}" for item in bank.items if isinstance(item, NumberItem)
             for note in item.notes]
    notes += [f"{left.key}: not exported ({left.reason})" for left in bank.left_out]
    return tuple(notes)


def _ident(text: str) -> str:
    return "mechgrade_" + re.sub(r"[^A-Za-z0-9_]", "_", text)


def _xml_bytes(root: ET.Element) -> bytes:
    ET.indent(root)
    return ET.tostring(root, encoding="utf-8", xml_declaration=True)


def number_text(value: float) -> str:
    """A number as both LMSs read it back exactly (shortest repr, no exponent marks Canvas's
    ``to_f`` or PHP's ``is_numeric`` would refuse).

    >>> number_text(15.84), number_text(1e-05), number_text(3.0)
    ('15.84', '1e-05', '3')
    """
    text = repr(float(value))
    return text[:-2] if text.endswith(".0") else text


def _html(parts) -> str:
    """The question's HTML: text escaped, paragraphs kept, variables as ``[name]`` or
    ``{name}`` (``parts`` already rendered to text)."""
    text = "".join(parts)
    paragraphs = [p.strip() for p in re.split(r"\n\s*\n", text) if p.strip()]
    return "".join(f"<p>{p}</p>" for p in paragraphs)


def _rendered(item, placeholder: Callable[[Variable], str]) -> list[str]:
    """The statement and prompt, HTML-escaped, each variable written by ``placeholder``."""
    if isinstance(item, EssayItem):
        return [html.escape(item.text), "\n\n", html.escape(item.prompt)]
    out = [placeholder(p) if isinstance(p, Variable) else html.escape(p) for p in item.text]
    return [*out, "\n\n", html.escape(item.prompt)]


# ---------------------------------------------------------------------------------- Canvas


def _sub(parent: ET.Element, tag: str, text: str | None = None, **attributes) -> ET.Element:
    node = ET.SubElement(parent, tag, {k: str(v) for k, v in attributes.items()})
    if text is not None:
        node.text = text
    return node


def _field(parent: ET.Element, label: str, entry: str) -> None:
    node = _sub(parent, "qtimetadatafield")
    _sub(node, "fieldlabel", label)
    _sub(node, "fieldentry", entry)


def canvas_assessment(bank: QuestionBank, ident: str) -> ET.Element:
    """The QTI 1.2 ``questestinterop`` of ``bank`` (see module doc)."""
    root = ET.Element("questestinterop", {
        "xmlns": QTI_NAMESPACE, "xmlns:xsi": "http://www.w3.org/2001/XMLSchema-instance",
        "xsi:schemaLocation": f"{QTI_NAMESPACE} {QTI_SCHEMA}"})
    assessment = _sub(root, "assessment", ident=ident, title=bank.title)
    meta = _sub(assessment, "qtimetadata")
    _field(meta, "cc_maxattempts", "1")
    section = _sub(assessment, "section", ident="root_section")
    for n, item in enumerate(bank.items, start=1):
        _canvas_item(section, item, f"{ident}_q{n}")
    return root


def _canvas_item(section: ET.Element, item, ident: str) -> None:
    essay = isinstance(item, EssayItem)
    node = _sub(section, "item", ident=ident, title=item.name)
    meta = _sub(_sub(node, "itemmetadata"), "qtimetadata")
    _field(meta, "question_type", "essay_question" if essay else "calculated_question")
    _field(meta, "points_possible", number_text(item.points))
    answer_ids = "" if essay else ",".join(f"{ident}_v{i}" for i in range(len(item.answers)))
    _field(meta, "original_answer_ids", answer_ids)
    presentation = _sub(node, "presentation")
    text = "<div>" + _html(_rendered(item, lambda v: f"[{v.name}]")) + "</div>"
    _sub(_sub(presentation, "material"), "mattext", text, texttype="text/html")
    response = _sub(presentation, "response_str", ident="response1", rcardinality="Single")
    fib = _sub(response, "render_fib", **({} if essay else {"fibtype": "Decimal"}))
    _sub(fib, "response_label", ident="answer1", **({"rshuffle": "No"} if essay else {}))
    processing = _sub(node, "resprocessing")
    _sub(_sub(processing, "outcomes"), "decvar", maxvalue="100", minvalue="0",
         varname="SCORE", vartype="Decimal")
    if essay:  # qti_items.rb essay_resprocessing: other_respcondition
        condition = _sub(processing, "respcondition", **{"continue": "No"})
        _sub(_sub(condition, "conditionvar"), "other")
        return
    for title, score, negate in (("correct", "100", False), ("incorrect", "0", True)):
        condition = _sub(processing, "respcondition", title=title)
        holder = _sub(condition, "conditionvar")
        _sub(_sub(holder, "not") if negate else holder, "other")
        _sub(condition, "setvar", score, varname="SCORE", action="Set")
    calculated = _sub(_sub(node, "itemproc_extension"), "calculated")
    tolerance = (f"{number_text(item.relative * 100)}%" if item.relative is not None
                 else number_text(item.absolute))
    _sub(calculated, "answer_tolerance", tolerance)
    _sub(calculated, "formulas", decimal_places=item.decimals)
    variables = _sub(calculated, "vars")
    for i, var in enumerate(item.variables):
        column = [values[i] for values in item.values]
        declared = _sub(variables, "var", name=var.name, scale=var.decimals)
        _sub(declared, "min", number_text(min(column)))
        _sub(declared, "max", number_text(max(column)))
    sets = _sub(calculated, "var_sets")
    for i, (values, answer) in enumerate(zip(item.values, item.answers)):
        var_set = _sub(sets, "var_set", ident=f"{ident}_v{i}")
        for var, value in zip(item.variables, values):
            _sub(var_set, "var", number_text(value), name=var.name)
        _sub(var_set, "answer", number_text(answer))


def _manifest(ident: str) -> ET.Element:
    """The content package's manifest: one QTI assessment resource (``imsqti_xmlv1p2``, the
    type Canvas's QTI export gives it)."""
    root = ET.Element("manifest", {"identifier": f"{ident}_manifest",
                                   "xmlns": MANIFEST_NAMESPACE})
    metadata = _sub(root, "metadata")
    _sub(metadata, "schema", "IMS Content")
    _sub(metadata, "schemaversion", "1.1.3")
    _sub(root, "organizations")
    resources = _sub(root, "resources")
    resource = _sub(resources, "resource", identifier=ident, type="imsqti_xmlv1p2")
    _sub(resource, "file", href=f"{ident}/{ident}.xml")
    return root


# ---------------------------------------------------------------------------------- Moodle


def _text(parent: ET.Element, tag: str, text: str = "", **attributes) -> ET.Element:
    node = _sub(parent, tag, **attributes)
    _sub(node, "text", text)
    return node


def moodle_quiz(bank: QuestionBank) -> ET.Element:
    """The Moodle XML ``<quiz>`` of ``bank`` (see module doc)."""
    quiz = ET.Element("quiz")
    category = _sub(quiz, "question", type="category")
    _text(category, "category", f"$course$/mechgrade/{bank.assignment_id}")
    for item in bank.items:
        if isinstance(item, EssayItem):
            _moodle_essay(quiz, item)
        elif item.variables:
            _moodle_calculated(quiz, item)
        else:
            _moodle_numerical(quiz, item)
    return quiz


MoodleType = Literal["essay", "numerical", "calculated"]
"""The Moodle XML question types written (a ``<question type=...>``)."""


def _header(quiz: ET.Element, kind: MoodleType, item) -> ET.Element:
    question = _sub(quiz, "question", type=kind)
    _text(question, "name", item.name)
    text = _html(_rendered(item, lambda v: "{" + v.name + "}"))
    _text(question, "questiontext", text, format="html")
    _text(question, "generalfeedback", "", format="html")
    _fields(question, defaultgrade=number_text(item.points), penalty="0.3333333", hidden="0")
    return question


def _fields(parent: ET.Element, **fields: str) -> None:
    for tag, text in fields.items():
        _sub(parent, tag, text)


def _moodle_essay(quiz: ET.Element, item: EssayItem) -> None:
    question = _header(quiz, "essay", item)
    _fields(question, responseformat="plain", responserequired="1", responsefieldlines="3",
            attachments="0", attachmentsrequired="0")
    _text(question, "graderinfo", "Graded by mechgrade from the quiz's responses.",
          format="html")
    _text(question, "responsetemplate", "", format="html")


def _tolerance(item: NumberItem) -> tuple[str, str]:
    """(tolerance, tolerancetype): 1 relative, 2 nominal (absolute)."""
    if item.relative is not None:
        return number_text(item.relative), "1"
    assert item.absolute is not None  # a number item has one of them
    return number_text(item.absolute), "2"


def _units(question: ET.Element, item: NumberItem) -> None:
    units = _sub(question, "units")
    names = [(item.unit, 1.0)]
    base = unit_text(si_unit(item.unit))
    if base and base != item.unit:
        names.append((base, si_factor(item.unit) / si_factor(base)))
    for name, multiplier in names:
        unit = _sub(units, "unit")
        _sub(unit, "multiplier", f"{multiplier:.12g}")
        _sub(unit, "unit_name", name)
    _fields(question, unitgradingtype="0", unitpenalty="0.1000000", showunits="0",
            unitsleft="0")


def _moodle_numerical(quiz: ET.Element, item: NumberItem) -> None:
    question = _header(quiz, "numerical", item)
    (answer,) = item.answers
    margin = item.absolute if item.absolute is not None else abs(answer) * (item.relative or 0)
    node = _sub(question, "answer", fraction="100", format="moodle_auto_format")
    _sub(node, "text", number_text(answer))
    _text(node, "feedback", "", format="html")
    _sub(node, "tolerance", number_text(margin))
    _units(question, item)


def _moodle_calculated(quiz: ET.Element, item: NumberItem) -> None:
    question = _header(quiz, "calculated", item)
    _fields(question, synchronize="0", single="0", answernumbering="abc", shuffleanswers="0")
    for feedback in ("correctfeedback", "partiallycorrectfeedback", "incorrectfeedback"):
        _text(question, feedback, "", format="html")
    tolerance, kind = _tolerance(item)
    node = _sub(question, "answer", fraction="100")
    _sub(node, "text", "{" + ANSWER + "}")
    _sub(node, "tolerance", tolerance)
    _sub(node, "tolerancetype", kind)
    _sub(node, "correctanswerformat", "1")
    _sub(node, "correctanswerlength", str(item.decimals))
    _text(node, "feedback", "", format="html")
    _units(question, item)
    definitions = _sub(question, "dataset_definitions")
    columns = [(var.name, [values[i] for values in item.values], var.decimals)
               for i, var in enumerate(item.variables)]
    columns.append((ANSWER, list(item.answers), 10))
    for name, values, decimals in columns:
        definition = _sub(definitions, "dataset_definition")
        _text(definition, "status", "private")
        _text(definition, "name", name)
        _sub(definition, "type", "calculated")
        _text(definition, "distribution", "uniform")
        _text(definition, "minimum", number_text(min(values)))
        _text(definition, "maximum", number_text(max(values)))
        _text(definition, "decimals", str(decimals))
        _sub(definition, "itemcount", str(len(values)))
        items = _sub(definition, "dataset_items")
        for n, value in enumerate(values, start=1):
            entry = _sub(items, "dataset_item")
            _sub(entry, "number", str(n))
            _sub(entry, "value", number_text(value))
        _sub(definition, "number_of_items", str(len(values)))


ANSWER = "mg_answer"
"""The dataset holding each variant's answer: the answer formula is ``{mg_answer}`` (a dynamics
answer has no formula; the solver's value per variant is the dataset)."""
