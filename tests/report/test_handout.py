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
    assert [p.name for p in written] == ["evil.html", "evil.md", "evil.txt", "givens.csv"]
    html = (tmp_path / "evil.html").read_text()
    assert "<script>alert" not in html and "&lt;script&gt;alert(1)&lt;/script&gt;" in html
    md = (tmp_path / "evil.md").read_text()
    assert r"\<script\>alert(1)\</script\> \*x\*" in md
    assert r"Speed \*of\* the tip. In m/s. Answer key `p.speed`" in md


def test_the_givens_table_has_one_row_per_student_with_its_draw_number():
    rows = givens_table((sheet("a", "A"), sheet("b", "B", draw=3)))
    assert rows == [["id", "name", "seed", "p.L", "p.L unit", "p draw"],
                    ["a", "A", "fall", "2.5", "m", 0], ["b", "B", "fall", "2.5", "m", 3]]


def test_a_statement_wrapped_in_the_spec_is_one_paragraph_on_the_page(tmp_path):
    wrapped = Sheet("hw", "Hw", "s1", "Ana", "fall", (
        SheetProblem("p", "P", "A rod of length\n2 m turns.\n\nFind <its> speed.\n", (),
                     (Question("p.v", "v?", "m/s"),)),))
    write_handouts((wrapped,), tmp_path)
    html = (tmp_path / "s1.html").read_text()
    assert "<p>A rod of length 2 m turns.</p>" in html
    assert "<p>Find &lt;its&gt; speed.</p>" in html


def test_a_missing_template_is_named(tmp_path):
    (tmp_path / "t").mkdir()
    with pytest.raises(MechgradeError, match=r"expected a template 'handout.html.j2', found none"):
        write_handouts((sheet(),), tmp_path / "out", tmp_path / "t")


def test_each_sheet_draws_the_mechanism_with_the_students_numbers_and_no_motion(tmp_path):
    import re

    from mechgrade.grade.assignment import load_assignment
    from mechgrade.grade.run import plan_assignment
    from mechgrade.grade.variants import handout_sheets
    from mechgrade.resources import shipped_dir

    plan = plan_assignment(load_assignment(shipped_dir("examples") / "hw2_variants"
                                           / "assignment.yaml"))
    sheets = handout_sheets(plan, [("20001", "Ana"), ("20002", "Ben")])
    write_handouts(sheets, tmp_path)
    tips = []
    for student in ("20001", "20002"):
        page = (tmp_path / f"{student}.html").read_text(encoding="utf-8")
        assert page.count("<svg") == 2 and "velocity (longest" not in page
        pendulum = page[page.index("<svg"):page.index("</svg>")]
        tips.append(re.findall(r'<circle cx="([\d.]+)" cy="([\d.]+)"', pendulum))
        assert "<svg" not in (tmp_path / f"{student}.md").read_text(encoding="utf-8")
    lengths = {g.value for s in sheets for g in s.problems[0].givens if g.name == "L"}
    # two students with different lengths or angles see two different drawings
    assert len(lengths) == 2 and tips[0] != tips[1]
    # the problem without variants is drawn once for every sheet
    assert sheets[0].problems[1].picture is sheets[1].problems[1].picture


def test_the_sheet_says_what_file_to_hand_in_with_every_answer_key(tmp_path):
    write_handouts((sheet(),), tmp_path)
    html = (tmp_path / "20001.html").read_text()
    assert ("<p>One text file named <code>20001.txt</code>, which comes with this sheet with "
            "every answer key in it: write each answer after its key and <code>=</code>, such "
            "as <code>p.speed = 12.5 m/s</code>. A line starting with <code>#</code> is not "
            "read.</p>") in html
    assert "<li>Speed *of* the tip. In m/s. Answer key <code>p.speed</code></li>" in html
    assert "<li>x? In m. Answer key <code>q.x</code></li>" in html
    md = (tmp_path / "20001.md").read_text()
    assert ("One text file named `20001.txt`, which comes with this sheet with every answer "
            "key in it: write each answer after its key and `=`, such as `p.speed = 12.5 m/s`. "
            "A line starting with `#` is not read.") in md


def test_how_each_answer_is_written_follows_its_kind():
    from mechgrade.report.handout import how_to_answer
    from mechgrade.spec.model import ObjectiveKind

    assert [how_to_answer(Question("p.q", "?", unit, kind)) for unit, kind in (
        ("m/s", ObjectiveKind.SCALAR), ("N", ObjectiveKind.VECTOR),
        ("m/s^2", ObjectiveKind.SYMBOLIC), ("", ObjectiveKind.SCALAR),
        ("", ObjectiveKind.VECTOR))] == [
        "In m/s.", "In N, as components in brackets: (x, y, z).",
        "As an expression, without a unit.", "A number without a unit.",
        "A number, as components in brackets: (x, y, z)."]


def test_each_student_gets_an_answer_file_with_every_key_named_like_their_feedback(tmp_path):
    from mechgrade.grade.results import AssignmentInfo, GradeReport, StudentResult
    from mechgrade.grade.submissions import read_submissions
    from mechgrade.report.output import feedback_names

    ids = ["20001", "../evil", "Zoë Ng"]
    write_handouts(tuple(sheet(i) for i in ids), tmp_path / "sheets")
    feedback = feedback_names(GradeReport(AssignmentInfo("hw2", "Hw"), (), tuple(
        StudentResult(i, "", "missing", 0.0, 1.0) for i in ids)))
    assert sorted(p.name for p in (tmp_path / "sheets").glob("*.txt")) == \
        sorted(name + ".txt" for name in feedback)
    assert (tmp_path / "sheets" / "20001.txt").read_text() == (
        "# Homework <2>: answers of Ana (id 20001)\n"
        "# Hand in this file, named 20001.txt: write each answer after its '=', as the\n"
        "# line above it says. A line starting with # is not read.\n"
        "\n"
        "# Pendulum\n"
        "# 1. Speed *of* the tip. In m/s.\n"
        "p.speed =\n"
        "\n"
        "# Fixed\n"
        "# 1. x? In m.\n"
        "q.x =\n")
    # handed in as it came, it answers nothing and is read without a complaint; filled in,
    # its answers are read
    folder = tmp_path / "submissions"
    folder.mkdir()
    blank = (tmp_path / "sheets" / "20001.txt").read_text()
    (folder / "20001.txt").write_text(blank)
    (folder / "20002.txt").write_text(blank.replace("p.speed =", "p.speed = 4.2 m/s")
                                      .replace("q.x =", "q.x = (1, 2) m"))
    read = {s.student: s for s in read_submissions(folder).students}
    assert read["20001"].messages == () and read["20002"].messages == ()
    assert [text for _, text in read["20001"].answers] == ["", ""]
    assert read["20002"].answers == (("p.speed", "4.2 m/s"), ("q.x", "(1, 2) m"))
