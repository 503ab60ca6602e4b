"""Starting specs: every template passes check as written and follows the schema."""

from __future__ import annotations

import jsonschema
import pytest
import yaml

from mechgrade.check import check_problem, written_tolerance
from mechgrade.errors import OutputError, SpecError
from mechgrade.resources import shipped_dir
from mechgrade.spec import load_problem, load_problem_text, problem_schema
from mechgrade.spec.load import SCHEMA_PATH
from mechgrade.spec.starter import (TEMPLATES, check_problem_id, schema_reference, starter_spec,
                                    write_starter)


def test_every_template_file_is_offered():
    files = sorted(p.name for p in (shipped_dir("templates") / "new").glob("*.yaml.j2"))
    assert files == sorted(f"{name}.yaml.j2" for name in TEMPLATES)


SLOWEST_TO_CHECK = frozenset({"rolling-body", "incline-friction", "pin-body"})
"""Starters whose `check` takes over 4 s (their generated mistakes are derived): `pytest -m
slow` checks them; the default command checks the impact and vibration starters' dynamics."""


@pytest.mark.parametrize("template", [
    pytest.param(name, marks=pytest.mark.slow) if name in SLOWEST_TO_CHECK else name
    for name in TEMPLATES])
def test_starter_passes_check_with_every_objective_tested(template, tmp_path):
    report = check_problem(write_starter("hw1_p1", template, tmp_path))
    assert report.error is None, report.error
    assert report.passed, [o.message for o in report.outcomes] + list(report.faults)
    assert report.warnings == ()
    assert report.untested == ()
    assert len(report.outcomes) >= 3


@pytest.mark.parametrize("template", TEMPLATES)
def test_starter_validates_with_a_standard_json_schema_validator(template):
    doc = yaml.safe_load(starter_spec("hw1_p1", template, schema_ref="s.json"))
    assert list(jsonschema.Draft202012Validator(problem_schema()).iter_errors(doc)) == []
    assert doc["id"] == "hw1_p1"


@pytest.mark.parametrize("template", TEMPLATES)
def test_starter_teaches_each_section_in_comments(template):
    text = starter_spec("p", template, schema_ref="s.json")
    comments = "\n".join(line for line in text.splitlines() if line.lstrip().startswith("#"))
    for word in ("inertial", "Points", "Givens", "Objectives", "unit"):
        assert word.lower() in comments.lower(), word


def test_starter_names_the_schema_relative_to_its_folder(tmp_path):
    path = write_starter("p", "particle", tmp_path)
    first = path.read_text(encoding="utf-8").splitlines()[0]
    ref = first.split("$schema=")[1]
    assert ref == schema_reference(tmp_path)
    assert (tmp_path / ref).resolve() == SCHEMA_PATH.resolve()


def test_rigid_body_template_points_to_the_kinetics_templates():
    text = " ".join(starter_spec("p", "rigid-body", schema_ref="s.json").replace("#", "").split())
    assert "not in the spec format" not in text
    assert "For its kinetics (mass, inertia, the forces on it and the pin's reaction) start " \
           "from `mechgrade new --template pin-body`" in text


@pytest.mark.parametrize("template", ["incline-friction", "pin-body", "rolling-body", "impact",
                                      "vibration"])
def test_kinetics_templates_state_the_kind_of_every_reaction(template):
    problem = load_problem_text(starter_spec("p", template, schema_ref="s.json"), "p.yaml")
    assert problem.dynamics is not None
    assert all("kind:" in line for line in starter_spec("p", template, schema_ref="s.json")
               .splitlines() if "{body:" in line and "direction" in line)
    assert all(r.kind != "reaction" for r in problem.dynamics.reactions)


@pytest.mark.parametrize("bad", ["hw3.p1", "hw-3", "3p", "", "../x", "p 1", "é"])
def test_problem_id_outside_the_identifier_rule_is_refused(bad):
    with pytest.raises(SpecError, match="expected letters, digits and '_' starting with a letter"):
        check_problem_id(bad)


def test_unknown_template_is_refused():
    with pytest.raises(SpecError, match="expected a template among particle, rotating-frame"):
        starter_spec("p", "orbit", schema_ref="s.json")


def test_existing_file_is_never_overwritten(tmp_path):
    (tmp_path / "p.yaml").write_text("mine\n", encoding="utf-8")
    with pytest.raises(OutputError, match="expected a new file, found an existing one"):
        write_starter("p", "particle", tmp_path)
    assert (tmp_path / "p.yaml").read_text(encoding="utf-8") == "mine\n"


def test_missing_folder_is_refused(tmp_path):
    with pytest.raises(OutputError, match="expected an existing folder"):
        write_starter("p", "particle", tmp_path / "nowhere")


@pytest.mark.parametrize("template", TEMPLATES)
def test_starter_expects_are_written_to_tight_digits(template, tmp_path):
    problem = load_problem(write_starter("p", template, tmp_path))
    loose = []
    for objective in problem.objectives:
        written = objective.expect.written
        for text in (written if isinstance(written, tuple) else (written,)):
            if isinstance(text, str) and float(text) != 0 and \
                    written_tolerance(text) > 2e-3 * abs(float(text)):
                loose.append((objective.id, text))
    assert loose == []
