"""The SVG picture of a mechanism at the instant (``mechgrade solve --plot``)."""

import re

import pytest
from click.testing import CliRunner

from mechgrade.cli import main
from mechgrade.resources import shipped_dir
from mechgrade.solve import solve
from mechgrade.solve.picture import (Scene, SceneBody, ScenePoint, SceneSupport, SupportKind,
                                     described, picture_svg, scene, unit_vector_svg)
from mechgrade.solve.result import Solution, StateValue
from mechgrade.spec import load_problem
from mechgrade.spec.dynamics import OutlineKind

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
    assert "velocity (longest 19 ft/s)" in svg and unit_vector_svg("B.x") in svg  # the problem's units


@pytest.mark.slow
def test_solve_plot_writes_an_svg_that_chromium_renders(tmp_path, chromium):
    out = tmp_path / "tube.svg"
    result = CliRunner().invoke(main, ["solve", str(TUBE), "--plot", str(out)])
    assert result.exit_code == 0, result.output
    dom, log = chromium(out)
    assert "<svg" in dom and "Uncaught" not in log


# ---------------------------------------------------------------------------- the mechanism


def _given_scene(name: str) -> Scene:
    """The scene at the givens alone (nothing solved: the picture needs only positions)."""
    problem = load_problem(shipped_dir("problems") / f"{name}.yaml")
    state = tuple(StateValue(g.key.text, g.value, g.unit, True, g.si) for g in problem.givens)
    return scene(problem, Solution(problem.id, (), state))


def test_an_atwood_machine_hangs_two_blocks_from_one_string_over_a_pulley():
    s = _given_scene("atwood_machine")
    assert [b.kind for b in s.bodies] == [OutlineKind.PARTICLE] * 2
    (string,) = s.supports
    assert string.kind == SupportKind.STRING and string.bodies == ("block1", "block2")
    assert [tuple(round(c, 9) for c in d) for d in string.directions] == [(0, 1, 0)] * 2
    svg = picture_svg(s)
    assert svg.count('class="pulley"') == 1 and svg.count('<rect class="body"') == 2
    assert svg.count('class="ground"') == 1  # the ceiling the pulley hangs from
    assert "string T pulling block1 and block2" in svg
    # O is at block1's centre: the frame's unit vectors are drawn in a corner, off the block
    (block1,) = re.findall(r'<rect class="body" data-body="block1" x="(-?\d+)" y="(-?\d+)"', svg)
    frame = re.search(r'marker-end="url\(#atwood_machine-f\)">\n<path d="M(-?\d+),(-?\d+)', svg)
    x, y = int(frame.group(1)), int(frame.group(2))
    assert not (int(block1[0]) - 10 <= x <= int(block1[0]) + 38
                and int(block1[1]) - 10 <= y <= int(block1[1]) + 38)


def test_a_rod_pendulum_is_drawn_its_full_length_from_its_pin():
    s = _given_scene("pendulum_pin_reaction")
    (rod,) = s.bodies
    assert rod.kind == OutlineKind.ROD and rod.sizes == (pytest.approx(1.2),)
    svg = picture_svg(s)
    assert 'class="pin"' in svg and "rod, a rod 1.2 m long" in svg
    # the rod's path runs from the pin O (one end) through G to the far end
    ends = re.search(r'<path class="body" data-body="rod" d="M(-?\d+),(-?\d+)L(-?\d+),(-?\d+)"',
                     svg).groups()
    pin = re.search(r'<circle cx="(-?\d+)" cy="(-?\d+)" r="4.5"', svg).groups()
    assert pin in (ends[:2], ends[2:])


def test_springs_and_dampers_between_one_pair_of_points_lie_side_by_side():
    s = _given_scene("two_mass_spring_chain")
    kinds = [(x.kind, x.bodies) for x in s.supports]
    assert kinds == [(SupportKind.SPRING, ("ground", "block1")),
                     (SupportKind.SPRING, ("block1", "block2")),
                     (SupportKind.DAMPER, ("block1", "block2"))]
    svg = picture_svg(s)
    assert svg.count('class="spring"') == 2 and svg.count('class="damper"') == 1
    assert svg.count('class="ground"') == 1  # the wall at the first spring's fixed end
    starts = {k: re.findall(rf'class="{k}" d="M(-?\d+),(-?\d+)', svg)
              for k in ("spring", "damper")}
    # the second spring and the damper join P1 to P2: across the line from each other
    assert abs(int(starts["spring"][1][1]) - int(starts["damper"][0][1])) >= 18


def test_a_block_on_an_incline_sits_square_to_the_hatched_surface():
    s = _given_scene("block_sliding_down_incline")
    (surface,) = s.supports
    assert surface.kind == SupportKind.SURFACE
    assert [round(c, 6) for c in surface.directions[0]] == [0.5, 0.866025, 0]
    svg = picture_svg(s)
    assert 'transform="rotate(30 ' in svg and 'class="ground"' in svg
    assert "block on a fixed surface" in svg


def test_a_string_round_a_corner_turns_over_a_pulley_there():
    cord = SceneSupport(SupportKind.STRING, "T", ((0.0, 0.0, 0.0), (1.0, -1.0, 0.0)),
                        ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0)), ("A", "B"))
    s = Scene("p", (ScenePoint("P", (0, 0, 0), None, None, None),
                    ScenePoint("Q", (1, -1, 0), None, None, None)), (),
              bodies=(SceneBody("A", OutlineKind.PARTICLE, (0, 0, 0)),
                      SceneBody("B", OutlineKind.PARTICLE, (1, -1, 0))), supports=(cord,))
    svg = picture_svg(s)
    (pulley,) = re.findall(r'class="pulley" cx="(\d+)" cy="(\d+)"', svg)
    marks = {tuple(m) for m in re.findall(r'<circle cx="(\d+)" cy="(\d+)" r="3.5"', svg)}
    p, q = sorted(marks)  # the pulley sits level with P and above Q
    assert pulley == (q[0], p[1])


def test_a_movable_pulley_wraps_its_body_and_the_strand_beyond_it_is_tied_up():
    up = (0.0, 1.0, 0.0)
    cord = SceneSupport(SupportKind.STRING, "T", ((0, 0, 0), (1, -0.5, 0), (1.4, -0.5, 0)),
                        (up, up, up), ("A", "B", "B"))
    s = Scene("p", (ScenePoint("A", (0, 0, 0), None, None, None),
                    ScenePoint("B", (1.2, -0.5, 0), None, None, None)), (),
              bodies=(SceneBody("A", OutlineKind.PARTICLE, (0, 0, 0)),
                      SceneBody("B", OutlineKind.PARTICLE, (1.2, -0.5, 0))), supports=(cord,))
    svg = picture_svg(s)
    assert svg.count('class="pulley"') == 2  # one fixed above, one on body B
    # B is that pulley (a light one's axle): no block drawn over it; A, held, is a block
    assert 'data-body="B"' not in svg and svg.count('<rect class="body"') == 1
    assert svg.count('class="ground"') == 2  # the fixed pulley's hanger and the tied strand


def test_collinear_arrows_are_drawn_apart_and_round_off_is_not_drawn():
    s = Scene("p", (ScenePoint("O", (0, 0, 0), None, None, None),
                    ScenePoint("A", (1, 0, 0), (2, 0, 0), (3, 0, 0), "O")), ())
    svg = picture_svg(s)
    velocity, acceleration = (re.search(rf'<g stroke="{c}"[^>]*>\n<path d="([^"]+)"', svg)[1]
                              for c in ("#1565c0", "#c62828"))
    assert velocity != acceleration
    still = Scene("p", (ScenePoint("O", (0, 0, 0), None, None, None),
                        ScenePoint("A", (1, 0, 0), (4e-16, 0, 0), None, "O")), ())
    assert "velocity" not in picture_svg(still)


def test_labels_keep_clear_of_each_other():
    s = Scene("p", tuple(ScenePoint(n, (x, 0, 0), None, None, None)
                         for n, x in (("A", 0.0), ("B", 0.02), ("C", 1.0))), ())
    svg = picture_svg(s)
    (ax, ay), (bx, by) = (tuple(float(c) for c in re.search(rf'<text x="([\d.]+)" y="([\d.]+)"'
                                                             rf'[^>]*>{n}<', svg).groups())
                          for n in "AB")
    assert abs(ax - bx) > 10 or abs(ay - by) > 14


def test_the_picture_says_its_bodies_and_supports_in_words():
    s = Scene("p", (ScenePoint("O", (0, 0, 0), None, None, None),), (),
              bodies=(SceneBody("disk", OutlineKind.DISK, (0, 0, 0), (0.5,)),),
              supports=(SceneSupport(SupportKind.PIN, "R", ((0, 0, 0),), (), ("disk",)),))
    assert described(s) == ("Bodies: disk, a disk of radius 0.5 m. Supports: disk pinned to "
                            "the ground. Point O.")


def test_a_body_given_by_its_inertia_entries_is_a_box_not_a_dot():
    s = Scene("p", (ScenePoint("O", (0, 0, 0), None, None, None),), (),
              bodies=(SceneBody("drum", OutlineKind.BODY, (0, 0, 0)),))
    svg = picture_svg(s)
    assert re.search(r'<rect class="body" data-body="drum" [^>]*rx="14"', svg)
    assert '<circle class="body"' not in svg


def test_a_points_label_keeps_off_the_block_drawn_on_it():
    # the Atwood machine's O and P1 coincide at block 1: their label "O, P1" sat on the block
    svg = picture_svg(_given_scene("atwood_machine"))
    blocks = [tuple(int(v) for v in m) for m in re.findall(
        r'data-body="block\d" x="(-?\d+)" y="(-?\d+)" width="(\d+)" height="(\d+)"', svg)]
    (x, y), = [tuple(int(v) for v in m) for m in re.findall(r'<text x="(\d+)" y="(\d+)"[^>]*>O, P<tspan baseline-shift="sub" font-size="8">1</tspan><', svg)]
    width = 8.6 * len("O, P1")  # as the picture reckons a label's width
    for bx, by, bw, bh in blocks:
        assert x + width <= bx or x >= bx + bw or y <= by or y - 12 >= by + bh, (x, y, bx, by)


def test_a_picture_inline_leaves_its_style_to_the_page_and_on_its_own_keeps_it():
    s = _given_scene("atwood_machine")
    alone, inline = picture_svg(s), picture_svg(s, inline=True)
    assert alone.startswith('<svg xmlns="http://www.w3.org/2000/svg"') and "paint-order" in alone
    assert 'xmlns' not in inline and "paint-order" not in inline and "\n" not in inline
    assert inline.count('class="halo"') == alone.count('paint-order="stroke"')
