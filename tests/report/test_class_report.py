"""The class report: statistics, HTML presentation, and a look in headless Chromium."""

from __future__ import annotations

import itertools
import re
import subprocess
from dataclasses import replace
from pathlib import Path

import pytest

from mechgrade.export import read_results
from mechgrade.grade.results import (AnswerResult, AssignmentInfo, GradeReport, ObjectiveInfo,
                                     SkippedEntry, StudentResult)
from mechgrade.report.class_report import (class_statistics, render_class_report,
                                           write_class_report)

DATA = Path(__file__).parent.parent / "data" / "export"


@pytest.fixture
def report():
    return read_results(DATA / "results.json")


def test_counts_and_score_summary_use_graded_students(report):
    stats = class_statistics(report, charts=False)
    assert (stats.students, stats.graded, stats.missing, stats.unreadable) == (7, 5, 1, 1)
    assert stats.mean == pytest.approx((10 + 5.5 + 3 + 3 + 7) / 5)
    assert (stats.lowest, stats.highest, stats.median, stats.max_score) == (3, 10, 5.5, 10)


def test_objective_success_wrong_answers_and_diagnoses(report):
    stats = class_statistics(report, charts=False)
    a_b = stats.objectives[1]
    assert (a_b.problem, a_b.objective, a_b.graded) == ("p1", "a_B", 5)
    assert a_b.success_rate == pytest.approx(1 / 5)
    assert a_b.mean_fraction == pytest.approx((1 + 0.25 + 0 + 0 + 0.25) / 5)
    assert [(d.label, d.count, d.share) for d in a_b.diagnoses] == \
        [("dropped the Coriolis term", 3, 0.6)]
    assert [(w.label, w.count) for w in a_b.wrong_answers] == [("-omega**2*r", 3)]
    assert {c.label: c.count for c in a_b.verdicts} == \
        {"correct": 1, "partial": 2, "incorrect": 1, "missing": 1}


def test_difficulty_and_discrimination_follow_their_definitions(report):
    stats = class_statistics(report, charts=False)
    p1, p2 = stats.problems
    assert p1.difficulty == pytest.approx((7 / 7 + 4 / 7 + 0 + 0 + 4 / 7) / 5)
    assert p2.difficulty == pytest.approx((1 + 0.5 + 1 + 1 + 1) / 5)
    # Corrected item-total correlation of p1: its credit against the points on p2.
    xs = [1, 4 / 7, 0, 0, 4 / 7]
    ys = [3, 1.5, 3, 3, 3]
    mx, my = sum(xs) / 5, sum(ys) / 5
    r = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / (
        sum((x - mx) ** 2 for x in xs) * sum((y - my) ** 2 for y in ys)) ** 0.5
    assert p1.discrimination == pytest.approx(r)


def test_discrimination_is_none_with_too_few_students():
    obj = ObjectiveInfo("p1", "v", "speed", 1.0)
    one = StudentResult("s", "S", "graded", 1.0, 1.0, (AnswerResult("p1", "v", "x", "correct",
                                                                    1.0, 1.0),))
    stats = class_statistics(GradeReport(AssignmentInfo("a", "A"), (obj,), (one,)),
                             charts=False)
    assert stats.problems[0].discrimination is None and stats.stdev is None


def test_students_with_missing_or_unreadable_answers_are_listed(report):
    issues = {i.id: i for i in class_statistics(report, charts=False).issues}
    assert set(issues) == {"s1004", "s1005", "s1006"}
    assert issues["s1004"].status == "missing" and issues["s1004"].detail == \
        "no submission file found"
    assert issues["s1006"].objectives == "p1.v_B (could not be read), p1.a_B (no answer)"


def test_an_empty_class_still_renders(report):
    empty = replace(report, students=())
    html = render_class_report(class_statistics(empty))
    assert "0</b><span>graded submissions" in html and "<svg" in html


def test_html_escapes_student_text_and_embeds_svg_charts(report, tmp_path):
    evil = replace(report.students[3], id="s666", name="<script>alert(1)</script>")
    out = tmp_path / "r.html"
    write_class_report(replace(report, students=report.students + (evil,)), out)
    html = out.read_text(encoding="utf-8")
    assert "<script" not in html and "&lt;script&gt;" in html
    assert html.count("<svg") == 2 and "<?xml" not in html
    assert "60 %</b> dropped the Coriolis term" in html
    assert not re.search(r"(src|href)=\"(https?:)?//", html)  # opens offline


@pytest.mark.slow
def test_report_opens_in_headless_chromium_without_console_errors(report, tmp_path, chromium):
    out = tmp_path / "class_report.html"
    write_class_report(report, out)
    dom, log = chromium(out)
    assert "CONSOLE" not in log and "Uncaught" not in log
    for marker in ('id="histogram"', 'id="success-chart"', 'id="objective-table"',
                   'id="problem-table"', 'id="issue-table"', "<svg", "<rect"):
        assert marker in dom


def large_class(n: int = 300) -> GradeReport:
    """``n`` students, every fifth one without a submission, the rest with one answer missing."""
    objectives = (ObjectiveInfo("p1", "v", "speed", 2.0), ObjectiveInfo("p1", "a", "accel", 2.0))
    students = []
    for i in range(n):
        if i % 5 == 0:
            students.append(StudentResult(f"s{i:04d}", f"Student {i}", "missing", 0.0, 4.0,
                                          messages=("no submission file found",)))
            continue
        answers = (AnswerResult("p1", "v", "3 m/s", "correct", 2.0, 2.0),
                   AnswerResult("p1", "a", None, "missing", 0.0, 2.0))
        students.append(StudentResult(f"s{i:04d}", f"Student {i}", "graded", 2.0, 4.0, answers))
    return GradeReport(AssignmentInfo("hw", "HW"), objectives, tuple(students))


def test_a_long_issue_list_is_folded_and_its_count_is_a_summary_card():
    html = render_class_report(class_statistics(large_class(), charts=False))
    assert '<details id="issues-details">' in html
    assert "<summary>300 students with a missing or unreadable submission or answer</summary>" \
        in html
    assert re.search(r'id="issues-card"><b>300</b>', html)


def test_a_short_issue_list_stays_open(report):
    html = render_class_report(class_statistics(report, charts=False))
    assert '<details id="issues-details" open>' in html
    assert re.search(r'id="issues-card"><b>3</b>', html)


@pytest.mark.slow  # a slow end-to-end check (over 5 s)
def test_a_300_student_report_stays_short_in_chromium(tmp_path, chromium):
    """The page of a 300-student class, drawn by Chromium, ends within 5000 pixels (the
    unfolded issue table alone took some 14000)."""
    from PIL import Image

    out = tmp_path / "class_report.html"
    write_class_report(large_class(), out)
    dom, _ = chromium(out)
    assert '<details id="issues-details">' in dom
    tall = tmp_path / "tall.png"
    subprocess.run(["chromium", "--headless", "--no-sandbox", "--disable-gpu",
                    f"--user-data-dir={tmp_path / 'tall-profile'}", f"--screenshot={tall}",
                    "--window-size=1200,12000", out.as_uri()],
                   capture_output=True, timeout=120, check=True)
    page = Image.open(tall).convert("L")
    width, height = page.size
    inked = [y for y in range(0, height, 20)
             if any(page.getpixel((x, y)) < 240 for x in range(0, width, 10))]
    assert 1500 < max(inked) < 5000


def test_objectives_are_named_by_their_titles_with_their_whole_keys(report):
    html = render_class_report(class_statistics(report))
    assert ('<tr><td>Speed of collar B<code class="key">p1.v_B</code></td>\n'
            '        <td class="n">3</td>') in html
    assert '<h3>Angular acceleration of the bar <code class="key">p2.alpha</code></h3>' in html
    assert "p1/v_B" not in html and "word-break: break-all" not in html
    # the chart's bars are labelled by title too, and say what they show
    assert ">Speed of collar B</text>" in html or "Speed of collar B" in html.split(
        '<figure class="chart" id="success-chart"')[1].split("</figure>")[0]


def test_points_and_scores_are_written_as_the_feedback_pages_write_them(report):
    html = render_class_report(class_statistics(report, charts=False))
    assert "· 7 students · 10 points possible</p>" in html
    assert "<b>3–10</b><span>range</span>" in html and "<b>5.5</b><span>median score" in html
    assert '<td class="n">4</td>' in html and ".0</td>" not in html


def test_the_histogram_has_bins_of_one_point_on_a_34_point_scale():
    from mechgrade.report.class_report import score_bins

    edges = score_bins(34)
    assert len(edges) == 36 and {b - a for a, b in itertools.pairwise(edges)} == {1.0}
    assert edges[0] == -0.5 and edges[-1] == 34.5
    assert score_bins(200)[1] - score_bins(200)[0] == 5


def test_the_histogram_says_in_words_how_many_students_had_each_score(report):
    html = render_class_report(class_statistics(report))
    assert ('<title id="histogram-title">Score distribution (out of 10)</title><desc '
            'id="histogram-desc">2 students scored 3; 1 student scored 5.5; 1 student scored 7; '
            '1 student scored 10.</desc>') in html
    assert html.count('id="figure_1"') == 0 and 'id="histogram-figure_1"' in html


def test_a_count_of_one_takes_the_singular(report):
    one = replace(report, students=report.students[:4] + report.students[5:],
                  skipped=(SkippedEntry("ivan/.keep", "hidden (its name starts with '.')"),))
    html = render_class_report(class_statistics(one, charts=False))
    for text in ("<b>1</b><span>missing submission</span>",
                 "<b>0</b><span>unreadable submissions</span>",
                 "<b>1</b><span>skipped folder entry</span>",
                 "<summary>1 entry not read as anyone's answers</summary>",
                 '<b>2</b><span><a href="#issues">students with missing or unreadable '
                 "answers</a></span>"):
        assert text in html
