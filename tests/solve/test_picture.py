"""The SVG picture of a mechanism at the instant (``mechgrade solve --plot``)."""

from click.testing import CliRunner

from mechgrade.cli import main
from mechgrade.solve.picture import picture_svg, scene
from mechgrade.resources import shipped_dir
from mechgrade.solve import solve
from mechgrade.spec import load_problem

TUBE = shipped_dir("problems") / "ruina_10_4_10_7_rotating_tube_accel.yaml"


def test_the_scene_has_each_points_motion_in_inertial_components():
    problem = load_problem(TUBE)
    points = {p.name: p for p in scene(problem, solve(problem)).points}
    ft = 0.3048
    assert [round(c / ft, 6) for c in points["P"].velocity] == [-10, 16, 0]
    assert [round(c / ft, 6) for c in points["P"].acceleration] == [-66, -40, 0]


def test_the_picture_labels_points_and_frames_and_is_the_same_each_time():
    problem = load_problem(TUBE)
    svg = picture_svg(scene(problem, solve(problem)))
    assert svg == picture_svg(scene(problem, solve(problem)))
    assert "velocity (longest" in svg and "B.x" in svg


def test_solve_plot_writes_an_svg_that_chromium_renders(tmp_path, chromium):
    out = tmp_path / "tube.svg"
    result = CliRunner().invoke(main, ["solve", str(TUBE), "--plot", str(out)])
    assert result.exit_code == 0, result.output
    dom, log = chromium(out)
    assert "<svg" in dom and "Uncaught" not in log
