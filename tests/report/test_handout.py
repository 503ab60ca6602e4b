"""Problem sheets: every text shown literally, safe file names, template errors located."""

from __future__ import annotations

import pytest

from mechgrade.errors import MechgradeError
from mechgrade.grade.results import VariantGiven
from mechgrade.grade.sheets import Question, Sheet, SheetProblem
from mechgrade.report.handout import givens_table, write_handouts


def sheet(student_id="20001", name="Ana", draw=0) -> Sheet:
    return Sheet("hw2", "Homework <2>", student_id, name, "fall", (
        SheetProblem("p", "Pendulum", "Length 2 m.", (VariantGiven("p", "L", 2.5, "m", draw),),
                     (Question("p.speed", "Speed *of* the tip.", "m/s"),)),
        SheetProblem("q", "Fixed", "No variants.", (), (Question("q.x", "x?", "m"),))))


def test_hostile_names_are_shown_literally_and_files_are_named_safely(tmp_path):
    written = write_handouts((sheet("../evil", "<script>alert(1)</script> *x*"),), tmp_path)
    assert [p.name for p in written] == ["evil.html", "evil.md", "givens.csv"]
    html = (tmp_path / "evil.html").read_text()
    assert "<script>alert" not in html and "&lt;script&gt;alert(1)&lt;/script&gt;" in html
    md = (tmp_path / "evil.md").read_text()
    assert r"\<script\>alert(1)\</script\> \*x\*" in md
    assert r"Speed \*of\* the tip. In m/s. Answer as `p.speed`" in md


def test_the_givens_table_has_one_row_per_student_with_its_draw_number():
    rows = givens_table((sheet("a", "A"), sheet("b", "B", draw=3)))
    assert rows == [["id", "name", "seed", "p.L", "p.L unit", "p draw"],
                    ["a", "A", "fall", "2.5", "m", 0], ["b", "B", "fall", "2.5", "m", 3]]


def test_a_missing_template_is_named(tmp_path):
    (tmp_path / "t").mkdir()
    with pytest.raises(MechgradeError, match="expected a template 'handout.html.j2', found none"):
        write_handouts((sheet(),), tmp_path / "out", tmp_path / "t")
