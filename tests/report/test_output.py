"""Writing a run's outputs: feedback pages, results.json, the CSVs, atomically and repeatably."""

from __future__ import annotations

import json

import pytest

from mechgrade.errors import MechgradeError
from mechgrade.expressions.loads import LoadKind
from mechgrade.grade.results import (AnswerResult, AssignmentInfo, GradeReport, LoadResult,
                                     ObjectiveInfo, StudentResult, Verdict)
from mechgrade.report import output
from mechgrade.report.output import (feedback_context, feedback_names, write_outputs)
from mechgrade.resources import shipped_dir

HOSTILE = '<script>alert("x")</script> *bold* `code` [link](http://e.vil)'

REPORT = GradeReport(
    AssignmentInfo("hw1", "Homework <1>"),
    (ObjectiveInfo("p", "acc", "Acceleration of A.", 2.0),
     ObjectiveInfo("p", "sym", "Speed in terms of L.", 3.0)),
    (StudentResult("ana", "Ana Ash", "graded", 3.5, 5.0, (
        AnswerResult("p", "acc", "98.5 ft/s^2", "correct", 2.0, 2.0, None, "Correct.",
                     "98.5 ft/s^2", "98.51 ft/s^2"),
        AnswerResult("p", "sym", "L*thetad**2", "partial", 1.5, 3.0, "sign error",
                     "Your answer has the wrong sign.", "L*thetad**2", "-L*thetad**2 ft/s^2"),
    ), ("read the key 'P.acc' as 'p.acc'",), (("email", "ana@uni.edu"),)),
     StudentResult("../eve", "", "graded", 0.0, 5.0, (
         AnswerResult("p", "acc", HOSTILE, "unreadable", 0.0, 2.0, None,
                      "Could not read the answer.", None, None),
         AnswerResult("p", "sym", None, "missing", 0.0, 3.0, None, "No answer was given."),
     ), (HOSTILE,)),
     StudentResult("joe", "Joe", "missing", 0.0, 5.0, (), ("no submission found",))),
)


def test_outputs_are_written_where_documented(tmp_path):
    written = write_outputs(REPORT, tmp_path).paths
    assert [p.relative_to(tmp_path).as_posix() for p in written] == [
        "results.json", "grades.csv", "results.csv", "feedback/ana.html", "feedback/ana.md",
        "feedback/eve.html", "feedback/eve.md", "feedback/joe.html", "feedback/joe.md"]
    assert not [p for p in tmp_path.rglob("*.tmp")]


def test_results_json_is_the_contract(tmp_path):
    write_outputs(REPORT, tmp_path)
    data = json.loads((tmp_path / "results.json").read_text(encoding="utf-8"))
    assert GradeReport.from_json(data) == REPORT
    assert list(data) == ["assignment", "objectives", "students", "skipped", "notes",
                          "internal_errors"]
    assert data["students"][0]["identity"] == {"email": "ana@uni.edu"}


def test_csvs_come_from_the_exporters(tmp_path):
    write_outputs(REPORT, tmp_path)
    grades = (tmp_path / "grades.csv").read_text(encoding="utf-8").splitlines()
    assert grades[0] == "id,name,status,p/acc,p/sym,total,max"
    results = (tmp_path / "results.csv").read_text(encoding="utf-8").splitlines()
    assert results[0] == "student,name,problem,objective,answer,verdict,points,max_points,diagnosis"


def test_rerun_gives_byte_identical_files(tmp_path):
    first, second = tmp_path / "a", tmp_path / "b"
    write_outputs(REPORT, first)
    write_outputs(REPORT, second)
    for path in sorted(first.rglob("*")):
        if path.is_file():
            assert path.read_bytes() == (second / path.relative_to(first)).read_bytes(), path


def test_html_feedback_shows_every_objective_and_escapes_student_text(tmp_path):
    write_outputs(REPORT, tmp_path)
    ana = (tmp_path / "feedback" / "ana.html").read_text(encoding="utf-8")
    assert "<title>Homework &lt;1&gt; – feedback for Ana Ash</title>" in ana
    assert '<b>3.5</b> <span>/ 5 points (70%)</span>' in ana
    assert '<dd class="verdict">Partly correct</dd>' in ana
    assert "<strong>Sign error:</strong>" in ana
    assert '<dt>Expected</dt><dd><span class="math">-L·θ̇² ft/s²</span></dd>' in ana
    assert '<span class="math">L·θ̇²</span>' in ana
    assert "read the key &#39;P.acc&#39; as &#39;p.acc&#39;" in ana
    eve = (tmp_path / "feedback" / "eve.html").read_text(encoding="utf-8")
    assert "<script>" not in eve
    assert "&lt;script&gt;alert(&#34;x&#34;)&lt;/script&gt;" in eve
    assert "<dt>Expected</dt>" not in eve
    assert "http" in eve and "<a " not in eve


def test_markdown_feedback_escapes_student_text(tmp_path):
    write_outputs(REPORT, tmp_path)
    eve = (tmp_path / "feedback" / "eve.md").read_text(encoding="utf-8")
    assert "- Your answer: \\<script\\>alert(\"x\")\\</script\\> \\*bold\\* \\`code\\` " \
           "\\[link\\](http://e.vil)" in eve
    ana = (tmp_path / "feedback" / "ana.md").read_text(encoding="utf-8")
    assert "# Homework \\<1\\>" in ana
    assert "**Score: 3.5 / 5 points (70%)**" in ana
    assert "## Speed in terms of L. — 1.5 / 3\n\nAnswer key `p.sym`\n" in ana
    assert "- Expected: -L·θ̇² ft/s²" in ana


def _answered_in_other_units(in_answer_unit: bool) -> GradeReport:
    extra = {"expected_in_answer_unit": "8.27 lbf"} if in_answer_unit else {}
    extra_w = {"expected_in_answer_unit": "(0, 0, -41.39) rpm"} if in_answer_unit else {}
    return GradeReport(
        AssignmentInfo("hw3", "Homework 3"),
        (ObjectiveInfo("p", "F", "Tension.", 1.0), ObjectiveInfo("p", "w", "Spin.", 1.0),
         ObjectiveInfo("p", "sym", "Speed.", 1.0)),
        (StudentResult("ana", "Ana", "graded", 2.0, 3.0, (
            AnswerResult("p", "F", "8.27 lbf", "correct", 1.0, 1.0, None, "Correct.",
                         "8.27 lbf", "36.79 N", **extra),
            AnswerResult("p", "w", "(0, 0, -41.4) rpm", "correct", 1.0, 1.0, None, "Correct.",
                         "(0, 0, -41.4) rpm", "(0, 0, -4.334) rad/s in frame B", **extra_w),
            AnswerResult("p", "sym", "L*w", "incorrect", 0.0, 1.0, None, "Not equivalent.",
                         "L*w", "L*w**2 m/s"),
        )),))


def test_expected_is_also_shown_in_the_unit_the_student_wrote(tmp_path):
    write_outputs(_answered_in_other_units(True), tmp_path)
    html = (tmp_path / "feedback" / "ana.html").read_text(encoding="utf-8")
    assert '<dt>Expected</dt><dd><span class="math">36.79 N (8.27 lbf)</span></dd>' in html
    assert ('<dt>Expected</dt><dd><span class="math">(0, 0, -4.334) rad/s in frame B '
            '((0, 0, -41.39) rpm)</span></dd>') in html
    assert '<dt>Expected</dt><dd><span class="math">L·w² m/s</span></dd>' in html
    markdown = (tmp_path / "feedback" / "ana.md").read_text(encoding="utf-8")
    assert "- Expected: 36.79 N (8.27 lbf)\n" in markdown
    assert "- Expected: (0, 0, -4.334) rad/s in frame B ((0, 0, -41.39) rpm)\n" in markdown
    assert "- Expected: L·w² m/s\n" in markdown


def test_a_results_json_from_before_the_students_unit_was_kept_renders_as_before(tmp_path):
    data = json.loads(json.dumps(_answered_in_other_units(True).to_json()))
    for answer in data["students"][0]["answers"]:
        del answer["expected_in_answer_unit"]
    old = GradeReport.from_json(data)
    assert old == _answered_in_other_units(False)
    write_outputs(old, tmp_path)
    html = (tmp_path / "feedback" / "ana.html").read_text(encoding="utf-8")
    assert '<dt>Expected</dt><dd><span class="math">36.79 N</span></dd>' in html
    assert "lbf)" not in html and "rpm)" not in html


def test_feedback_file_names_are_safe_and_unique():
    assert feedback_names(REPORT) == ["ana", "eve", "joe"]


def test_templates_folder_overrides_the_shipped_templates(tmp_path):
    templates = tmp_path / "t"
    templates.mkdir()
    (templates / "feedback.html.j2").write_text("<p>{{ student.display_name }}: "
                                                "{{ student.score }}</p>\n", encoding="utf-8")
    (templates / "feedback.md.j2").write_text("{{ student.id }}\n", encoding="utf-8")
    write_outputs(REPORT, tmp_path / "out", templates)
    assert (tmp_path / "out" / "feedback" / "ana.html").read_text(encoding="utf-8") == \
        "<p>Ana Ash: 3.5</p>\n"


def test_template_using_an_unknown_value_is_an_error(tmp_path):
    templates = tmp_path / "t"
    templates.mkdir()
    (templates / "feedback.html.j2").write_text("{{ student.grade_letter }}", encoding="utf-8")
    (templates / "feedback.md.j2").write_text("x", encoding="utf-8")
    with pytest.raises(MechgradeError, match="the template uses a value mechgrade does not "
                                             "provide"):
        write_outputs(REPORT, tmp_path / "out", templates)


def test_missing_or_broken_template_is_an_error(tmp_path):
    templates = tmp_path / "t"
    templates.mkdir()
    (templates / "feedback.html.j2").write_text("{% for %}", encoding="utf-8")
    with pytest.raises(MechgradeError, match="expected a valid Jinja template"):
        write_outputs(REPORT, tmp_path / "out", templates)
    (templates / "feedback.html.j2").write_text("ok", encoding="utf-8")
    with pytest.raises(MechgradeError, match=r"expected a template 'feedback.md.j2', found none"):
        write_outputs(REPORT, tmp_path / "out", templates)
    with pytest.raises(MechgradeError, match="expected a folder of templates, found none"):
        write_outputs(REPORT, tmp_path / "out", tmp_path / "nowhere")


def test_shipped_templates_are_autoescaped_and_strict():
    from mechgrade.report.output import template_environment

    env = template_environment()
    assert env.autoescape is True
    assert env.undefined.__name__ == "StrictUndefined"
    assert (shipped_dir("templates") / "feedback.html.j2").is_file()


def test_context_prepares_text_and_templates_compute_nothing():
    context = feedback_context(REPORT, REPORT.students[0])
    assert context["student"] == {"id": "ana", "name": "Ana Ash", "display_name": "Ana Ash",
                                  "status": "graded", "status_label": "Graded", "score": "3.5",
                                  "max_score": "5", "percent": "70%"}
    assert context["rows"][1]["prompt"] == "Speed in terms of L."
    assert context["reveal"] is True


def test_a_diagrams_rows_carry_their_verdict_as_a_verdict():
    diagram = AnswerResult("p", "fbd", "W: -m*g*N.y", Verdict.PARTIAL, 1.0, 2.0, loads=(
        LoadResult("weight", "W", LoadKind.WEIGHT, "G", "W: -m*g*N.y", (), ""),
        LoadResult("normal", "N_A", LoadKind.NORMAL, "A", None, ("missing",), "")))
    student = StudentResult("ana", "Ana", "graded", 1.0, 2.0, (diagram,))
    rows = feedback_context(REPORT, student)["rows"][0]["loads"]
    assert [row["verdict"] for row in rows] == [Verdict.CORRECT, Verdict.INCORRECT]
    assert all(isinstance(row["verdict"], Verdict) for row in rows)


def test_unwritable_output_folder_is_an_error(tmp_path):
    (tmp_path / "file").write_text("", encoding="utf-8")
    with pytest.raises(MechgradeError, match="cannot create the output folder"):
        write_outputs(REPORT, tmp_path / "file" / "out")


@pytest.mark.slow
def test_feedback_page_renders_in_headless_chromium(tmp_path, chromium):
    write_outputs(REPORT, tmp_path)
    dom, log = chromium(tmp_path / "feedback" / "ana.html")
    assert "CONSOLE" not in log and "Uncaught" not in log
    assert "Ana Ash" in dom and "98.5 ft/s^2" in dom and "Sign error" in dom
    # Hostile student text stays text: no script element came from it.
    hostile_dom, _ = chromium(next((tmp_path / "feedback").glob("*eve*.html")))
    assert "<script>alert" not in hostile_dom and "&lt;script&gt;" in hostile_dom


def test_an_authors_mistake_message_is_printed_once(tmp_path):
    message = "That is only the centripetal part; add the tangential part."
    report = GradeReport(AssignmentInfo("hw1", "HW"), (ObjectiveInfo("p", "a", "Acc.", 2.0),),
                         (StudentResult("ana", "Ana", "graded", 1.0, 2.0, (
                             AnswerResult("p", "a", "66.8 ft/s^2", "partial", 1.0, 2.0,
                                          message, message),)),))
    write_outputs(report, tmp_path)
    for suffix in (".html", ".md"):
        page = (tmp_path / "feedback" / f"ana{suffix}").read_text(encoding="utf-8")
        assert page.count("centripetal part") == 1, suffix


def _class_of(count):
    answers = lambda i: (AnswerResult("p", "acc", f"{i} ft/s^2", "partial", 1.0, 2.0, "sign error",
                                      "Your answer has the wrong sign.", f"{i} ft/s^2",
                                      "98.51 ft/s^2"),)
    return GradeReport(AssignmentInfo("hw1", "HW"), (ObjectiveInfo("p", "acc", "Acc.", 2.0),),
                       tuple(StudentResult(f"s{i}", f"S {i}", "graded", 1.0, 2.0, answers(i))
                             for i in range(count)))


def _files(folder):
    return {p.relative_to(folder).as_posix(): p.read_bytes()
            for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.fixture
def small_pieces(monkeypatch):
    """Pieces of two students, so that a small class is spread over the helpers."""
    monkeypatch.setattr(output, "PIECE_STUDENTS", 2)


def test_outputs_are_the_same_for_any_number_of_jobs(tmp_path, small_pieces):
    report = _class_of(9)
    written = {jobs: write_outputs(report, tmp_path / str(jobs), jobs=jobs) for jobs in (1, 2, 3)}
    assert [p.relative_to(tmp_path / "1") for p in written[1].paths] == \
        [p.relative_to(tmp_path / "3") for p in written[3].paths]
    assert _files(tmp_path / "1") == _files(tmp_path / "2") == _files(tmp_path / "3")
    assert len(_files(tmp_path / "1")) == 3 + 2 * 9


def test_a_template_breaking_for_some_students_stops_with_the_first_and_writes_nothing(
        tmp_path, small_pieces):
    templates = tmp_path / "t"
    templates.mkdir()
    (templates / "feedback.html.j2").write_text(
        '{% if student.id == "s7" %}{{ student.late }}{% endif %}'
        '{% if student.id == "s3" %}{{ student.early }}{% endif %}', encoding="utf-8")
    (templates / "feedback.md.j2").write_text("x", encoding="utf-8")
    for jobs in (1, 2, 3):
        out = tmp_path / f"out{jobs}"
        with pytest.raises(MechgradeError, match="has no attribute 'early'"):
            write_outputs(_class_of(9), out, templates, jobs=jobs)
        assert not [p for p in out.rglob("*") if p.is_file()]


def test_a_page_fault_is_recorded_in_student_order_with_any_jobs(tmp_path, small_pieces,
                                                                   monkeypatch):
    real = output._context

    def fails_for_some(report, student, prompts, markdown=False, names=None):
        if student.id in ("s2", "s7"):
            raise RuntimeError(f"no context for {student.id}")
        return real(report, student, prompts, markdown, names)

    monkeypatch.setattr(output, "_context", fails_for_some)
    reports = [write_outputs(_class_of(9), tmp_path / str(jobs), jobs=jobs).report
               for jobs in (1, 3)]
    assert reports[0] == reports[1]
    assert [e.split(":")[0] for e in reports[0].internal_errors] == [
        "feedback of 's2' (html)", "feedback of 's2' (md)", "feedback of 's7' (html)",
        "feedback of 's7' (md)"]
    assert _files(tmp_path / "1") == _files(tmp_path / "3")


@pytest.mark.parametrize("dies_in", ["_render_students", "_write_piece"])
def test_what_a_helper_that_died_left_is_done_here(tmp_path, small_pieces, monkeypatch,
                                                   dies_in):
    import os

    parent, real = os.getpid(), getattr(output, dies_in)

    def dies_in_a_helper(*args):
        if os.getpid() != parent:
            os._exit(1)
        return real(*args)

    write_outputs(_class_of(9), tmp_path / "alone", jobs=1)
    monkeypatch.setattr(output, dies_in, dies_in_a_helper)
    write_outputs(_class_of(9), tmp_path / "helped", jobs=3)
    assert _files(tmp_path / "alone") == _files(tmp_path / "helped")


def test_without_shared_memory_every_page_is_done_here(tmp_path, small_pieces, monkeypatch):
    import multiprocessing.context

    def no_shared_memory(*args, **kwargs):
        raise PermissionError("no /dev/shm")

    write_outputs(_class_of(5), tmp_path / "alone", jobs=1)
    monkeypatch.setattr(multiprocessing.context.BaseContext, "Value", no_shared_memory)
    write_outputs(_class_of(5), tmp_path / "here", jobs=3)
    assert _files(tmp_path / "alone") == _files(tmp_path / "here")


def test_a_page_spells_a_problems_coordinates_as_its_worked_solution_does():
    from mechgrade.grade.worked import FeedbackSolutions
    from mechgrade.solve.worked import WorkedSolution

    report = GradeReport(AssignmentInfo("hw", "Hw"), (ObjectiveInfo("p", "v", "Speed of J.", 1.0),),
                         (StudentResult("ana", "Ana", "graded", 0.0, 1.0, (
                             AnswerResult("p", "v", "2", "incorrect", 0.0, 1.0, None, "",
                                          "2", "k1*xjd m/s"),)),))
    ana = report.students[0]
    worked = FeedbackSolutions((WorkedSolution("p", "P", (), "", names=(("xj", "x_J"),)),))
    for markdown, shown in ((False, "k<sub>1</sub>·ẋ<sub>J</sub> m/s"), (True, "k₁·ẋ J m/s")):
        assert feedback_context(report, ana, markdown=markdown, worked=worked)[
            "rows"][0]["expected"] == shown
    # another problem's page knows nothing of it
    assert feedback_context(report, ana)["rows"][0]["expected"] == "k<sub>1</sub>·xjd m/s"
