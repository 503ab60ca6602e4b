"""The problem schema documents itself for editors, and the library's problems follow it."""

from __future__ import annotations

from pathlib import Path

import jsonschema
import pytest
import yaml
from sympy.physics.vector import ReferenceFrame

from mechgrade.mechanics.bodies import explicit_inertia
from mechgrade.spec import load_problem_text, problem_schema
from mechgrade.spec.load import SCHEMA_PATH
from mechgrade.units import parse_quantity

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = sorted((ROOT / "problems").glob("*.yaml"))
# the problem specs beside the example assignments (an assignment file is not a problem spec)
PROBLEMS += sorted(p for p in (ROOT / "examples").glob("*/*.yaml") if p.name != "assignment.yaml")
MODELINE = "# yaml-language-server: $schema="


def _subschemas(schema, path=()):
    """Every (path, subschema) of ``schema`` that is a mapping, depth first."""
    if isinstance(schema, dict):
        yield path, schema
        for key, value in schema.items():
            if key in ("examples", "default", "enum", "const"):
                continue
            yield from _subschemas(value, path + (key,))
    elif isinstance(schema, list):
        for i, value in enumerate(schema):
            yield from _subschemas(value, path + (i,))


def _properties():
    for path, sub in _subschemas(problem_schema()):
        for name, prop in sub.get("properties", {}).items():
            yield "/".join(map(str, path + ("properties", name))), prop


def test_the_schema_is_a_valid_draft_2020_12_schema():
    jsonschema.Draft202012Validator.check_schema(problem_schema())


def test_every_property_has_a_description_and_examples():
    undocumented = [p for p, prop in _properties() if not prop.get("description")]
    without_examples = [p for p, prop in _properties() if not prop.get("examples")]
    assert undocumented == []
    assert without_examples == []


def test_every_section_and_definition_has_a_description():
    schema = problem_schema()
    entries = [f"$defs/{k}" for k, v in schema["$defs"].items() if not v.get("description")]
    assert entries == []


def test_every_example_and_default_is_valid_for_its_field():
    validator = jsonschema.Draft202012Validator(problem_schema())
    invalid = []
    for path, prop in _properties():
        sub = {k: v for k, v in prop.items() if k not in ("examples", "default")}
        for value in prop.get("examples", []) + ([prop["default"]] if "default" in prop else []):
            if not validator.evolve(schema=sub).is_valid(value):
                invalid.append((path, value))
    assert invalid == []


def test_defaults_are_what_the_loader_takes_when_a_key_is_left_out():
    schema = problem_schema()
    objective = schema["properties"]["objectives"]["items"]["properties"]
    text = (ROOT / "tests" / "data" / "spec" / "base.yaml").read_text(encoding="utf-8")
    mistake = "\n    mistakes: [{find: 'mag(vel(P, N))*2', message: m}]"
    text = text.replace("    expect: {value: 6}", "    expect: {value: 6}" + mistake)
    problem = load_problem_text(text, "base.yaml")
    speed = problem.objectives[0]
    assert problem.consistency == schema["properties"]["consistency"]["default"]
    assert speed.tolerance.rel == objective["tolerance"]["properties"]["rel"]["default"]
    assert speed.tolerance.abs == objective["tolerance"]["properties"]["abs"]["default"]
    assert speed.mistakes[0].credit == objective["mistakes"]["items"]["properties"]["credit"][
        "default"]
    positive = schema["properties"]["parameters"]["additionalProperties"]["oneOf"][1]
    assert problem.parameters[0].positive is positive["properties"]["positive"]["default"]


def test_a_wrong_example_is_caught():
    validator = jsonschema.Draft202012Validator(problem_schema())
    identifier = {"$ref": "#/$defs/identifier"}
    assert not validator.evolve(schema=identifier).is_valid("2nd")


@pytest.mark.parametrize("path", PROBLEMS, ids=[p.stem for p in PROBLEMS])
def test_problem_validates_with_a_standard_json_schema_validator(path):
    doc = yaml.safe_load(path.read_text(encoding="utf-8"))
    errors = [e.message for e in jsonschema.Draft202012Validator(problem_schema()).iter_errors(doc)]
    assert errors == []


@pytest.mark.parametrize("path", PROBLEMS, ids=[p.stem for p in PROBLEMS])
def test_problem_names_the_shipped_schema_on_its_first_line(path):
    first = path.read_text(encoding="utf-8").splitlines()[0]
    assert first.startswith(MODELINE)
    assert (path.parent / first[len(MODELINE):]).resolve() == SCHEMA_PATH.resolve()


def test_dynamics_defaults_are_what_the_loader_and_the_core_take_when_a_key_is_left_out():
    schema = problem_schema()
    loads = schema["properties"]["loads"]["properties"]
    spring = loads["springs"]["additionalProperties"]["properties"]
    friction = loads["friction"]["additionalProperties"]["properties"]
    integrate = schema["properties"]["analysis"]["properties"]["integrate"]["properties"]
    about_centre = schema["$defs"]["inertia"]["properties"]["about_centre"]["properties"]

    def loaded(name, old, new):
        text = (ROOT / "problems" / f"{name}.yaml").read_text(encoding="utf-8")
        assert old in text
        return load_problem_text(text.replace(old, new), f"{name}.yaml").dynamics

    chain = loaded("two_mass_spring_chain", ", length: L2}", "}")
    assert chain.load("s2").length.text == str(spring["length"]["default"])
    incline = loaded("block_sliding_down_incline", "kind: kinetic}", "kind: kinetic}")  # as is
    assert incline.load("F_P").surface == friction["surface"]["default"]
    ladder = loaded("ladder_wall_lift_off", "    max_time: 10 s\n", "")
    assert ladder.analysis.max_time == parse_quantity(integrate["max_time"]["default"]).to_si()
    frame = ReferenceFrame("B")
    assert explicit_inertia({}, frame).to_matrix(frame).is_zero_matrix
    assert [about_centre[k]["default"] for k in about_centre] == [0] * 6
