"""``mechgrade catalog``: exit codes and exact text; a folder with a bad spec lists its error,
still writes the other pages and exits 1."""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from mechgrade.cli import main

DATA = Path(__file__).resolve().parents[1] / "data" / "catalog"


def run(*args: str):
    return CliRunner().invoke(main, list(args))


def test_a_bad_spec_is_listed_the_rest_is_written_and_the_exit_is_1(tmp_path):
    result = run("catalog", str(DATA / "mixed"), "--out", str(tmp_path))
    assert result.exit_code == 1
    assert result.stdout == (f"wrote {tmp_path / 'index.html'} and 1 problem page(s); "
                             "1 file(s) could not be shown\n")
    assert result.stderr == (f"{DATA / 'mixed' / 'broken.yaml'}:7:15: frames.A.parent: unknown "
                             "parent frame 'NN'; did you mean 'N'? (expected one of: N, A)\n")
    assert (tmp_path / "problems" / "pendulum_variants.html").is_file()
    assert "unknown parent frame &#39;NN&#39;" in (tmp_path / "index.html").read_text("utf-8")


def test_good_problems_exit_0(tmp_path):
    result = run("catalog", str(DATA / "mixed" / "pendulum_variants.yaml"), "--out",
                 str(tmp_path))
    assert (result.exit_code, result.stderr) == (0, "")
    assert result.stdout == (f"wrote {tmp_path / 'index.html'} and 1 problem page(s); "
                             "0 file(s) could not be shown\n")


def test_an_objective_not_solved_is_reported_and_the_exit_is_1(tmp_path):
    result = run("catalog", str(DATA / "unsolved"), "--out", str(tmp_path))
    assert result.exit_code == 1
    assert result.stderr == (f"{DATA / 'unsolved' / 'free_rate.yaml'}:24:5: objectives[1]: "
                             "objective 'speed' is not determined by the givens: give a value "
                             "for theta' (velocity level)\n")
    assert (tmp_path / "problems" / "free_rate.html").is_file()


def test_a_folder_without_problem_files_is_one_message_and_exit_2(tmp_path):
    result = run("catalog", str(tmp_path), "--out", str(tmp_path / "out"))
    assert result.exit_code == 2
    assert result.stderr == f"expected problem files (*.yaml), found none in {tmp_path}\n"
    assert not (tmp_path / "out").exists()


def test_an_output_folder_that_cannot_be_made_is_one_message_and_exit_2(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("", encoding="utf-8")
    result = run("catalog", str(DATA / "mixed" / "pendulum_variants.yaml"), "--out",
                 str(blocker / "out"))
    assert result.exit_code == 2
    assert result.stderr.startswith(f"{blocker / 'out'}: cannot create the output folder")
    assert result.stderr.count("\n") == 1


def test_out_is_required(tmp_path):
    result = run("catalog", str(DATA / "mixed"))
    assert result.exit_code == 2
    assert "Missing option '--out'" in result.stderr
