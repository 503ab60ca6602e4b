"""Canvas's QTI quiz import and grading, and the structure rules of IMS QTI 1.2 ASI, for the
tests.

**Structure.** The published schema (``http://www.imsglobal.org/xsd/ims_qtiasiv1p2p1.xsd``) is
not reachable from this machine (no network), so the content models and attributes of the
elements mechgrade writes are encoded here, from the IMS QTI ASI XML Binding v1.2 (the DTD the
XSD was generated from): :data:`CONTENT` gives each element's children as a regular
expression over child names, :data:`ATTRIBUTES` the required attributes and the enumerated
values. ``itemproc_extension`` holds any content (Canvas's ``calculated`` lives there).

**Import.** Canvas's own QTI export (canvas-lms ``lib/cc/qti/qti_generator.rb``,
``qti_items.rb``) and import of a calculated question (``gems/plugins/qti_exporter/lib/qti/
calculated_interaction.rb``): ``question_type`` and ``points_possible`` from the item's
``qtimetadata``; ``answer_tolerance`` read ``to_f`` when it holds only digits and dots, else
kept as text (``1%``); each ``var`` with ``scale`` (``to_i``), ``min`` and ``max``; each
``var_set`` with its ``var`` values and ``answer`` (``to_f``); ``formulas/@decimal_places``.

**Grading.** ``Quizzes::QuizQuestion::CalculatedQuestion``: the student's answer set is graded
as an exact answer with the question's tolerance as margin
(``Quizzes::QuizQuestion::NumericalQuestion#correct_answer_parts``: a margin ending in ``%``
is that share of the exact value; inclusive, in ``BigDecimal``).
"""

from __future__ import annotations

import io
import re
import xml.etree.ElementTree as ET
import zipfile
from dataclasses import dataclass
from decimal import Decimal

NS = "{http://www.imsglobal.org/xsd/ims_qtiasiv1p2}"
_CONDITION = "(not|and|or|unanswered|other|varequal|varlt|varlte|vargt|vargte|varsubset|" \
             "varinside|varsubstring|durequal|durlt|durlte|durgt|durgte|var_extension)"
CONTENT = {
    "questestinterop": r"(qticomment )?((objectbank )|(assessment )|((section |item )+))",
    "assessment": r"(qticomment )?(duration )?(qtimetadata )*(objectives )*"
                  r"(assessmentcontrol )*(rubric )*(presentation_material )?"
                  r"(outcomes_processing )*(assessproc_extension )?(assessfeedback )*"
                  r"(selection_ordering )?(reference )?((sectionref |section )+)",
    "section": r"(qticomment )?(duration )?(qtimetadata )*(objectives )*(sectioncontrol )*"
               r"(sectionprecondition )*(sectionpostcondition )*(rubric )*"
               r"(presentation_material )?(outcomes_processing )*(sectionproc_extension )?"
               r"(sectionfeedback )*(selection_ordering )?(reference )?"
               r"((itemref |item |sectionref |section )*)",
    "item": r"(qticomment )?(duration )?(itemmetadata )?(objectives )*(itemcontrol )*"
            r"(itemprecondition )*(itempostcondition )*((itemrubric |rubric )*)"
            r"(presentation )?(resprocessing )*(itemproc_extension )?(itemfeedback )*"
            r"(reference )?",
    "itemmetadata": r"(qtimetadata )*",
    "qtimetadata": r"(vocabulary )?(qtimetadatafield )+",
    "qtimetadatafield": r"fieldlabel fieldentry ",
    "presentation": r"(qticomment )?((material |response_lid |response_xy |response_str |"
                    r"response_num |response_grp |response_extension |flow )+)",
    "material": r"(qticomment )?((mattext |matemtext |matimage |mataudio |matvideo |"
                r"matapplet |matapplication |matref |matbreak |mat_extension )+)"
                r"(altmaterial )*",
    "response_str": r"(material )?(render_choice |render_hotspot |render_slider |"
                    r"render_fib |render_extension )(material )?",
    "render_fib": r"((material |material_ref |response_label |flow_label )*)",
    "response_label": r"((qticomment |mattext |matemtext |matimage |mataudio |matvideo |"
                      r"matapplet |matapplication |matbreak |matref |material |"
                      r"material_ref |flow_mat )*)",
    "resprocessing": r"(qticomment )?outcomes ((respcondition |itemproc_extension )+)",
    "outcomes": r"(qticomment )?((decvar (interpretvar )*)+)",
    "respcondition": r"(qticomment )?conditionvar (setvar )*(displayfeedback )*"
                     r"(respcond_extension )?",
    "conditionvar": rf"(({_CONDITION} )+)",
    "not": rf"{_CONDITION} ",
    "fieldlabel": "", "fieldentry": "", "mattext": "", "decvar": "", "setvar": "",
    "other": "",
}
ATTRIBUTES = {
    "assessment": {"ident": None},
    "section": {"ident": None},
    "item": {"ident": None},
    "response_str": {"ident": None, "rcardinality": ("Single", "Multiple", "Ordered")},
    "response_label": {"ident": None},
    "render_fib": {"fibtype": ("String", "Integer", "Decimal", "Scientific")},
    "decvar": {"vartype": ("Integer", "String", "Decimal", "Scientific", "Boolean",
                           "Enumerated", "Set")},
    "setvar": {"action": ("Set", "Add", "Subtract", "Multiply", "Divide")},
    "respcondition": {"continue": ("Yes", "No")},
    "mattext": {"texttype": None},
}
OPTIONAL_ATTRIBUTES = {"decvar", "setvar", "respcondition", "render_fib"}


def check_qti(root: ET.Element) -> None:
    """Fail (``AssertionError`` with the element's path) unless every element mechgrade
    writes follows its content model and attributes; an unknown element fails too."""
    def walk(node: ET.Element, path: str) -> None:
        name = node.tag.removeprefix(NS)
        here = f"{path}/{name}"
        if name == "itemproc_extension":
            return  # any content (Canvas's extension)
        assert name in CONTENT, f"{here}: not an element mechgrade may write"
        children = "".join(child.tag.removeprefix(NS) + " " for child in node)
        assert re.fullmatch(CONTENT[name], children), f"{here}: children {children!r}"
        if name in CONTENT and not CONTENT[name]:
            assert len(node) == 0, f"{here}: expected text only"
        for attribute, allowed in ATTRIBUTES.get(name, {}).items():
            value = node.get(attribute)
            if value is None:
                assert name in OPTIONAL_ATTRIBUTES, f"{here}: missing @{attribute}"
                continue
            assert allowed is None or value in allowed, f"{here}/@{attribute}: {value!r}"
        for child in node:
            walk(child, here)
    walk(root, "")


@dataclass
class CanvasQuestion:
    title: str
    question_type: str
    points: float
    text: str
    answer_tolerance: float | str | None = None
    decimal_places: int | None = None
    variables: list[dict] | None = None
    answers: list[dict] | None = None


def read_package(data: bytes) -> tuple[ET.Element, list[CanvasQuestion]]:
    """The assessment of a QTI package (found through ``imsmanifest.xml``'s resource of
    type ``imsqti_xmlv1p2``) and its questions as Canvas imports them."""
    with zipfile.ZipFile(io.BytesIO(data)) as archive:
        manifest = ET.fromstring(archive.read("imsmanifest.xml"))
        hrefs = [r.find("{*}file").get("href") for r in manifest.findall(".//{*}resource")
                 if r.get("type") == "imsqti_xmlv1p2"]
        assert len(hrefs) == 1, "one QTI assessment resource expected"
        root = ET.fromstring(archive.read(hrefs[0]))
    return root, [_question(item) for item in root.iter(f"{NS}item")]


def _meta(item: ET.Element) -> dict[str, str]:
    return {f.findtext(f"{NS}fieldlabel"): f.findtext(f"{NS}fieldentry") or ""
            for f in item.iter(f"{NS}qtimetadatafield")}


def _question(item: ET.Element) -> CanvasQuestion:
    meta = _meta(item)
    question = CanvasQuestion(item.get("title", ""), meta["question_type"],
                              float(meta["points_possible"]),
                              item.find(f"{NS}presentation/{NS}material/{NS}mattext").text or "")
    calculated = item.find(f"{NS}itemproc_extension/{NS}calculated")
    if question.question_type != "calculated_question":
        return question
    assert calculated is not None, "a calculated question without its calculated extension"
    tolerance = calculated.findtext(f"{NS}answer_tolerance")
    # calculated_interaction.rb: to_f unless something other than digits and dots
    question.answer_tolerance = float(tolerance) if tolerance is not None and \
        not re.search(r"[^\d.]", tolerance) else tolerance
    formulas = calculated.find(f"{NS}formulas")
    question.decimal_places = int(formulas.get("decimal_places", "0")) if formulas is not None \
        else None
    question.variables = [{"name": v.get("name"), "scale": int(v.get("scale", "0")),
                           "min": float(v.findtext(f"{NS}min")),
                           "max": float(v.findtext(f"{NS}max"))}
                          for v in calculated.iterfind(f"{NS}vars/{NS}var")]
    question.answers = [{"id": s.get("ident"),
                         "variables": {v.get("name"): float(v.text) for v in s.iterfind(f"{NS}var")},
                         "answer": float(s.findtext(f"{NS}answer"))}
                        for s in calculated.iterfind(f"{NS}var_sets/{NS}var_set")]
    return question


def canvas_accepts(question: CanvasQuestion, answer_set: dict, response: str) -> bool:
    """Whether Canvas marks ``response`` correct for a student given ``answer_set``."""
    exact = Decimal(repr(answer_set["answer"]))
    margin = question.answer_tolerance
    if str(margin).endswith("%"):
        margin = abs(float(str(margin)[:-1]) / 100.0 * float(exact))
    margin = Decimal(str(margin))
    number = Decimal(response)
    return exact - margin <= number <= exact + margin
