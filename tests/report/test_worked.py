"""The worked solution as a page: ``mechgrade solve --steps --format html|md``."""

from click.testing import CliRunner

from mechgrade.cli import main
from mechgrade.report.output import anchor as row_id
from mechgrade.resources import shipped_dir

TUBE = shipped_dir("problems") / "ruina_10_4_10_7_rotating_tube_accel.yaml"


def _solve(*args):
    result = CliRunner().invoke(main, ["solve", str(TUBE), *args])
    assert result.exit_code == 0, result.output
    return result.output


def test_the_html_solution_composes_the_acceleration_term_by_term_offline():
    text = _solve("--steps", "--format", "html")
    # omega and alpha of B; P's position; velocity: 2 terms and the sum; acceleration: 4 terms
    # and the sum; each row lays its math out inline (the page's style): no display attribute
    assert text.count('<math ') == 2 + 1 + 3 + 5 and 'display="block"' not in text
    for anchor in ("acc-P-alpha_r", "acc-P-omega_omega_r", "acc-P-coriolis", "acc-P-relative",
                   "answer-a_P_N", "givens"):
        assert f'id="{row_id("ruina_10_4_10_7_rotating_tube_accel", anchor)}"' in text
    # a step or a row no mistake happens in is no link's target: it carries no id (every
    # page has it)
    for anchor in ("acc-P-total", "acc-P"):
        assert f'id="{row_id("ruina_10_4_10_7_rotating_tube_accel", anchor)}"' not in text
    assert "<svg" in text and "<script" not in text
    assert "http" not in text.replace("http://www.w3.org/2000/svg", "")  # offline: no CDN


def test_rates_are_written_with_dots_and_vectors_with_their_frames():
    text = _solve("--steps", "--format", "html")
    # q: a small letter with no ascender, in math italic with combining dots
    dot_q, ddot_q = '<mi>\U0001d45e\u0307</mi>', '<mi>\U0001d45e\u0308</mi>'
    assert dot_q in text and ddot_q in text and "<mi>qd</mi>" not in text
    # the Coriolis term 2 ^N omega^B x ^B v^P = -2 q' y' b_x
    assert ("<mn>2</mn><mmultiscripts><mi mathvariant=\"bold\">ω</mi><none/><mi>B</mi>"
            "<mprescripts/><none/><mi>N</mi></mmultiscripts>") in text


def test_the_markdown_solution_lists_every_step_and_the_answers():
    text = _solve("--steps", "--format", "md")
    for heading in ("### Givens and what is asked", "### Frames and their angular velocities",
                    "### The acceleration of P in N (composed in frame B, from O)"):
        assert heading in text
    # the model's names as a textbook writes them, no code (issue 20)
    assert "- `2 ω x B v,P = - 2·q\u0307·\u1e8f·b-hat x`" in text
    assert "- `= (-66, -40, 0) ft/s² in frame N`" in text
    assert "- `q\u0308 = 3 rad/s²`" in text  # the given q'' as a textbook writes it


def test_author_text_with_backticks_stays_literal_in_the_markdown():
    """A prompt holding a backtick closed the code span its line was written in, and what
    followed (an <img onerror>) was raw HTML to a Markdown renderer."""
    from mechgrade.report.output import worked_markdown
    from mechgrade.solve.worked import WorkedSolution, WorkedStep

    prompt = "Magnitude of the `tip` acceleration <img src=x onerror=alert(1)> ``x"
    worked = WorkedSolution("p", "P", (
        WorkedStep("givens", "Givens and what is asked", ("L = 2 ft", "", f"acc_mag: {prompt}")),
        WorkedStep("answer-acc_mag", prompt, ("= 98.5 ft/s^2",))), "")
    lines = worked_markdown(worked).splitlines()
    # a code span fenced by more backticks than any run inside it: all of it literal
    assert f"- ``` acc_mag: {prompt} ```" in lines
    assert "#### Magnitude of the \\`tip\\` acceleration \\<img src=x onerror=alert(1)\\> " \
           "\\`\\`x" in lines


def test_code_spans_hold_any_text():
    from mechgrade.report.output import code_span

    assert code_span("a = 1") == "`a = 1`"
    assert code_span("`a` b") == "`` `a` b ``"
    assert code_span("x ``` y\n z") == "```` x ``` y z ````"
