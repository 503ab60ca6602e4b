"""Writing a run's outputs: feedback pages, results.json, the CSVs, atomically and repeatably."""

from __future__ import annotations

import json

import pytest

from mechgrade.errors import MechgradeError
from mechgrade.grade.results import (AnswerResult, AssignmentInfo, GradeReport, ObjectiveInfo,
                                     StudentResult)
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
    assert '<dt>Expected</dt><dd><span class="math">-L·thetad² ft/s²</span></dd>' in ana
    assert '<span class="math">L·thetad²</span>' in ana
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
    assert "## Speed in terms of L. — 1.5 / 3\n\np · sym\n" in ana
    assert "- Expected: -L·thetad² ft/s²" in ana


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
    with pytest.raises(MechgradeError, match="expected a template 'feedback.md.j2', found none"):
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


def test_unwritable_output_folder_is_an_error(tmp_path):
    (tmp_path / "file").write_text("", encoding="utf-8")
    with pytest.raises(MechgradeError, match="cannot create the output folder"):
        write_outputs(REPORT, tmp_path / "file" / "out")


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
