"""``mechgrade new`` and ``mechgrade schema``: exact texts and exit codes."""

from __future__ import annotations

import json

from click.testing import CliRunner

from mechgrade.cli import main
from mechgrade.spec.load import SCHEMA_PATH


def run(*args):
    return CliRunner().invoke(main, list(args))


def test_new_writes_the_spec_and_says_how_to_watch_it(tmp_path):
    result = run("new", "hw1_p1", "--template", "linkage", "--out", str(tmp_path))
    path = tmp_path / "hw1_p1.yaml"
    assert result.exit_code == 0
    assert result.output == (f"wrote {path} (template linkage)\n"
                             f"next: edit it, and watch it with `mechgrade check --watch {path}`\n")
    assert "title: A slider-crank" in path.read_text(encoding="utf-8")


def test_new_spec_passes_check(tmp_path):
    run("new", "hw1_p1", "--out", str(tmp_path))
    result = run("check", str(tmp_path / "hw1_p1.yaml"))
    assert result.output == (f"ok   {tmp_path / 'hw1_p1.yaml'} (5 tests, DOF 2)\n"
                             "1 file(s), 0 failing\n")
    assert result.exit_code == 0


def test_new_refuses_to_overwrite(tmp_path):
    (tmp_path / "p.yaml").write_text("mine\n", encoding="utf-8")
    result = run("new", "p", "--out", str(tmp_path))
    assert result.exit_code == 2
    assert result.output == (f"{tmp_path / 'p.yaml'}: expected a new file, found an existing one; "
                             "choose another ID or --out folder (new never overwrites)\n")
    assert (tmp_path / "p.yaml").read_text(encoding="utf-8") == "mine\n"


def test_new_refuses_a_bad_id(tmp_path):
    result = run("new", "hw-1", "--out", str(tmp_path))
    assert result.exit_code == 2
    assert result.output == ("ID: expected letters, digits and '_' starting with a letter (the id "
                             "is the file name and answers are named problem_id.objective_id), "
                             "found 'hw-1'\n")
    assert list(tmp_path.iterdir()) == []


def test_new_refuses_an_unknown_template(tmp_path):
    result = run("new", "p", "--template", "orbit", "--out", str(tmp_path))
    assert result.exit_code == 2
    assert ("'orbit' is not one of 'particle', 'rotating-frame', 'rolling', 'linkage', "
            "'rigid-body'") in result.output


def test_schema_prints_the_shipped_schema_path():
    result = run("schema")
    assert result.exit_code == 0
    assert result.output == f"{SCHEMA_PATH}\n"


def test_schema_out_writes_a_copy(tmp_path):
    out = tmp_path / "problem.schema.json"
    result = run("schema", "--out", str(out))
    assert result.exit_code == 0
    assert result.output == f"wrote {out}\n"
    assert json.loads(out.read_text(encoding="utf-8")) == json.loads(SCHEMA_PATH.read_text("utf-8"))


def test_schema_out_into_a_missing_folder_is_bad_input(tmp_path):
    result = run("schema", "--out", str(tmp_path / "no" / "s.json"))
    assert result.exit_code == 2
    assert result.output == (f"{tmp_path / 'no'}: expected an existing folder to write "
                             "'s.json' into, found none\n")
