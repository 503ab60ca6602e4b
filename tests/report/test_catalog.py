"""The catalogue's pages: an index of every problem with its topics, analyses and the files
that could not be shown, and a page per problem with its statement, picture, answers, worked
solution and variants."""

from __future__ import annotations

from pathlib import Path

import pytest

from mechgrade.errors import MechgradeError
from mechgrade.report.catalog import write_catalog
from mechgrade.grade.catalog import CatalogFault, catalog_entries

DATA = Path(__file__).resolve().parents[1] / "data" / "catalog"


@pytest.fixture(scope="module")
def entries():
    found, faults = catalog_entries([DATA / "mixed" / "pendulum_variants.yaml",
                                     DATA / "unsolved" / "free_rate.yaml"])
    assert faults == ()
    return found


def test_the_index_and_one_page_per_problem_are_written(entries, tmp_path):
    written = write_catalog(entries, (), tmp_path)
    assert [p.relative_to(tmp_path).as_posix() for p in written] == [
        "index.html", "problems/pendulum_variants.html", "problems/free_rate.html"]


def test_the_index_lists_each_problem_with_its_topics_analyses_and_link(entries, tmp_path):
    write_catalog(entries, (), tmp_path)
    index = (tmp_path / "index.html").read_text(encoding="utf-8")
    assert '<a href="problems/pendulum_variants.html">Acceleration of a pendulum tip ' \
           '(per-student numbers)</a>' in index
    assert 'data-topics="circular-motion particle-kinematics"' in index
    assert '<button type="button" class="chip" data-topic="circular-motion" ' \
           'aria-pressed="false">circular motion</button>' in index
    assert '<span class="kind">kinematics</span>' in index
    assert '<span class="bad">1 not solved</span>' in index
    assert "2 problems." in index and 'id="faults"' not in index


def test_a_problem_page_shows_statement_picture_answers_worked_solution_and_variants(
        entries, tmp_path):
    write_catalog(entries, (), tmp_path)
    page = (tmp_path / "problems" / "pendulum_variants.html").read_text(encoding="utf-8")
    assert "<p>A rigid pendulum of length 2 ft turns about a fixed pin O. Its body frame A is a " \
           "simple rotation theta" in page
    assert '<figure class="picture">\n<svg' in page
    assert '<td class="answer">37.7359 ft/s^2</td>' in page
    assert "<li>L: from 1.5 to 4 ft in steps of 0.1 ft</li>" in page
    assert "<li>theta&#39;&#39;: a whole number from 4 to 15 rad/s^2</li>" in page
    assert "<code>theta&#39;&#39; &gt; 0.2*theta&#39;^2</code>" in page
    assert '<details open>\n<summary>Worked solution</summary>\n<article class="ws"' in page
    assert page.count("<svg") == 1  # the picture once, beside the statement


def test_an_objective_not_solved_says_why_on_its_page(entries, tmp_path):
    write_catalog(entries, (), tmp_path)
    page = (tmp_path / "problems" / "free_rate.html").read_text(encoding="utf-8")
    assert '<td class="bad">not solved: ' in page
    assert "is not determined by the givens: give a value for theta&#39; (velocity level)" in page


def test_a_fault_is_listed_on_the_index_with_its_message_escaped(tmp_path):
    fault = CatalogFault("x.yaml", "x.yaml:1:1: title: expected text, found '<script>'")
    write_catalog((), (fault,), tmp_path)
    index = (tmp_path / "index.html").read_text(encoding="utf-8")
    assert "<h2>1 file could not be shown</h2>" in index
    assert "<li>x.yaml:1:1: title: expected text, found &#39;&lt;script&gt;&#39;</li>" in index


def test_a_missing_template_is_one_error_and_nothing_is_written(entries, tmp_path):
    templates = tmp_path / "templates"
    templates.mkdir()
    with pytest.raises(MechgradeError) as caught:
        write_catalog(entries, (), tmp_path / "out", templates)
    assert str(caught.value) == f"{templates}: expected a template 'catalog_index.html.j2', " \
                                "found none"
    assert not (tmp_path / "out").exists()


def test_an_output_folder_that_cannot_be_made_is_one_error(entries, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("", encoding="utf-8")
    with pytest.raises(MechgradeError) as caught:
        write_catalog(entries, (), blocker / "out")
    assert str(caught.value).startswith(f"{blocker / 'out'}: cannot create the output folder")


@pytest.mark.slow
def test_the_index_filters_in_headless_chromium_without_console_errors(entries, tmp_path,
                                                                         chromium):
    write_catalog(entries, (), tmp_path)
    page = tmp_path / "index_clicked.html"
    # the reader presses the "circular motion" topic: only the problem tagged with it stays
    text = (tmp_path / "index.html").read_text(encoding="utf-8")
    page.write_text(text.replace("</body>", '<script>document.querySelector('
                                 '"button[data-topic=circular-motion]").click();</script></body>'),
                    encoding="utf-8")
    dom, log = chromium(page)
    assert "CONSOLE" not in log and "Uncaught" not in log
    assert '<p id="shown">1 of 2 shown</p>' in dom
    assert dom.count(" hidden=\"\"") == 1 and 'aria-pressed="true">circular motion' in dom
