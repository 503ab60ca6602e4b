"""The worked derivation as a page: ``mechgrade solve --steps --format html|md``."""

from click.testing import CliRunner

from mechgrade.cli import main
from mechgrade.resources import shipped_dir

TUBE = shipped_dir("problems") / "ruina_10_4_10_7_rotating_tube_accel.yaml"


def _solve(*args):
    result = CliRunner().invoke(main, ["solve", str(TUBE), *args])
    assert result.exit_code == 0, result.output
    return result.output


def test_the_html_derivation_shows_vectors_as_mathml_that_chromium_renders(tmp_path, chromium):
    page = tmp_path / "steps.html"
    page.write_text(_solve("--steps", "--format", "html"), encoding="utf-8")
    text = page.read_text(encoding="utf-8")
    assert text.count('<math display="block">') == 2 and "<script" not in text
    assert "http" not in text  # offline: no CDN
    dom, log = chromium(page)
    assert "<math" in dom and "Uncaught" not in log


def test_the_markdown_derivation_lists_every_section_and_the_answers():
    text = _solve("--steps", "--format", "md")
    for heading in ("## Frames", "## Velocities", "## Accelerations", "## Objectives"):
        assert heading in text
    assert "- `a_P_N         (-66, -40, 0) ft/s^2 in N`" in text
