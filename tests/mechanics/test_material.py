"""Material points: the motion asked of a point fixed in no body, where a body's material point
sits, is flagged; a point meant to slide along its body is not."""

from __future__ import annotations

from pathlib import Path

from mechgrade.mechanics import derive
from mechgrade.spec import load_problem

DATA = Path(__file__).resolve().parents[1] / "data" / "authoring_mistakes"


def test_a_velocity_given_on_a_contact_point_suggests_the_material_point():
    warnings = derive(load_problem(DATA / "solve_material_point.yaml")).warnings
    assert [w.where.field for w in warnings] == ["givens.dot(vel(T, N), N.x)"]
    assert warnings[0].message.endswith("write 'vel(coincident(T, Disk), N)'")


def test_a_collar_located_along_its_rod_is_not_flagged():
    assert derive(load_problem(DATA / "solve_degenerate_branch.yaml")).warnings == ()


def test_a_point_fixed_in_its_body_is_not_flagged():
    text = (DATA / "solve_speed_given_branch.yaml").read_text()
    assert derive(load_problem(DATA / "solve_speed_given_branch.yaml")).warnings == ()
    assert "vel(P, N)" in text


def test_a_material_point_written_of_a_material_point_in_a_constraint_is_read(tmp_path):
    problem = tmp_path / "solve_material_point.yaml"
    problem.write_text((DATA / "solve_material_point.yaml").read_text().replace(
        "    rolling: {body: Disk, contact: T, surface: N}",
        "    velocity: vel(coincident(coincident(T, Disk), Disk), N) = vel(coincident(T, N), N)"))
    warnings = derive(load_problem(problem)).warnings
    assert [w.where.field for w in warnings] == ["givens.dot(vel(T, N), N.x)"]
