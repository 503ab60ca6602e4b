"""An output folder replaced whole: interrupted runs cleared, the instructor's files kept, one
run at a time, nothing left beside it."""

from __future__ import annotations

import json
import os
import stat

import pytest

from mechgrade import outfolder
from mechgrade.errors import OutputError
from mechgrade.outfolder import OutputKind, claim

KIND = OutputKind("mechgrade demo", "a.txt", ("a.txt", "pages/*.md"))


def write_run(out, files: dict[str, str]):
    """One run of KIND writing ``files``; what it committed."""
    with claim(out, KIND) as folder:
        for name, text in files.items():
            (folder.staging / name).parent.mkdir(parents=True, exist_ok=True)
            (folder.staging / name).write_text(text, encoding="utf-8")
        return folder.commit({"n": len(files)}, inputs=())


def contents(folder) -> dict[str, str]:
    return {p.relative_to(folder).as_posix(): p.read_text(encoding="utf-8")
            for p in sorted(folder.rglob("*")) if p.is_file() and p.name != "manifest.json"}


def test_nothing_but_the_folder_is_left_beside_it(tmp_path):
    write_run(tmp_path / "out", {"a.txt": "1", "pages/x.md": "x"})
    write_run(tmp_path / "out", {"a.txt": "2"})
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]
    assert contents(tmp_path / "out") == {"a.txt": "2"}


def test_what_an_interrupted_run_left_beside_the_folder_is_cleared_and_said(tmp_path):
    out = tmp_path / "out"
    write_run(out, {"a.txt": "1"})
    unfinished = tmp_path / ".out.mechgrade-new.0badc0de"
    (unfinished / "pages").mkdir(parents=True)
    (unfinished / "pages" / "half.md").write_text("ha", encoding="utf-8")
    done = write_run(out, {"a.txt": "2"})
    assert done.notes == ("removed what an interrupted run left (.out.mechgrade-new.0badc0de)",)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


def test_a_run_cut_between_its_two_renames_gets_the_previous_outputs_back(tmp_path):
    # where the two folders cannot be swapped in one step: out was set aside, the new one not
    # yet in its place
    out = tmp_path / "out"
    write_run(out, {"a.txt": "1", "pages/x.md": "x"})
    os.rename(out, tmp_path / ".out.mechgrade-old.12345678")
    (tmp_path / ".out.mechgrade-new.87654321").mkdir()
    with claim(out, KIND) as folder:
        assert contents(out) == {"a.txt": "1", "pages/x.md": "x"}
        assert folder.previous == {"a.txt", "pages/x.md"}
        assert folder.notes == [
            "put back the outputs an interrupted run had set aside (.out.mechgrade-old.12345678)",
            "removed what an interrupted run left (.out.mechgrade-new.87654321)"]


def test_where_folders_cannot_be_swapped_in_one_step_two_renames_do_it(tmp_path, monkeypatch):
    monkeypatch.setattr(outfolder, "_exchange", lambda new, target: False)
    out = tmp_path / "out"
    write_run(out, {"a.txt": "1", "pages/x.md": "x"})
    (out / "mine.txt").write_text("mine", encoding="utf-8")
    done = write_run(out, {"a.txt": "2"})
    assert contents(out) == {"a.txt": "2", "mine.txt": "mine"}
    assert done.removed == ("pages/x.md",) and done.kept == ("mine.txt",)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


def test_the_instructors_files_links_and_empty_folders_are_kept_as_they_are(tmp_path):
    out = tmp_path / "out"
    write_run(out, {"a.txt": "1"})
    (out / "mine.txt").write_text("mine", encoding="utf-8")
    inode = (out / "mine.txt").stat().st_ino
    (out / "link").symlink_to("mine.txt")
    (out / "empty").mkdir()
    done = write_run(out, {"a.txt": "2"})
    assert done.kept == ("link", "mine.txt")
    assert (out / "mine.txt").stat().st_ino == inode  # the same file, not a copy
    assert os.readlink(out / "link") == "mine.txt"
    assert (out / "empty").is_dir()
    manifest = json.loads((out / "manifest.json").read_text(encoding="utf-8"))
    assert manifest["files"] == ["a.txt"] and manifest["kept"] == ["link", "mine.txt"]
    assert manifest["arguments"] == {"n": 1} and manifest["command"] == "mechgrade demo"


def test_a_file_of_the_instructors_where_the_run_writes_one_is_never_replaced(tmp_path):
    out = tmp_path / "out"
    write_run(out, {"a.txt": "1"})
    (out / "pages").mkdir()
    (out / "pages" / "new.md").write_text("mine", encoding="utf-8")
    with pytest.raises(OutputError) as raised:
        write_run(out, {"a.txt": "2", "pages/new.md": "generated"})
    assert str(raised.value) == (
        f"{out}: --out: expected no file of yours where this run writes its outputs, found "
        f"pages/new.md (kept as they are: mechgrade never replaces a file it did not write); "
        f"move them away and run again")
    assert contents(out) == {"a.txt": "1", "pages/new.md": "mine"}
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


def test_the_folders_permissions_are_kept(tmp_path):
    out = tmp_path / "out"
    write_run(out, {"a.txt": "1", "pages/x.md": "x"})
    os.chmod(out, 0o750)
    os.chmod(out / "pages", 0o700)
    write_run(out, {"a.txt": "2", "pages/y.md": "y"})
    assert stat.S_IMODE(out.stat().st_mode) == 0o750
    assert stat.S_IMODE((out / "pages").stat().st_mode) == 0o700


def test_a_file_or_the_current_folder_as_the_output_folder_is_refused(tmp_path, monkeypatch):
    (tmp_path / "f").write_text("x", encoding="utf-8")
    with pytest.raises(OutputError, match="--out: expected a folder, found a file"):
        write_run(tmp_path / "f", {})
    (tmp_path / "out" / "inner").mkdir(parents=True)
    monkeypatch.chdir(tmp_path / "out" / "inner")
    with pytest.raises(OutputError) as raised:
        write_run(tmp_path / "out", {})
    assert str(raised.value) == (
        f"{tmp_path / 'out'}: --out: expected a folder that does not hold the current folder, "
        f"found the current folder inside it (a run replaces --out whole); run from another "
        f"folder, or choose another --out")


def test_the_folders_made_for_a_run_that_failed_are_removed(tmp_path):
    with pytest.raises(RuntimeError):
        with claim(tmp_path / "a" / "b" / "out", KIND):
            raise RuntimeError("the run failed")
    assert list(tmp_path.iterdir()) == []


def test_a_worker_forked_during_a_run_does_not_hold_its_lock(tmp_path):
    read, write = os.pipe()
    with claim(tmp_path / "out", KIND):
        (held,) = outfolder._LOCKS
        pid = os.fork()
        if pid == 0:  # the worker: is the lock's file still open here?
            try:
                os.fstat(held)
                os.write(write, b"open")
            except OSError:
                os.write(write, b"closed")
            os._exit(0)
        os.waitpid(pid, 0)
    assert os.read(read, 16) == b"closed"
    os.close(read)
    os.close(write)


@pytest.mark.skipif(os.geteuid() == 0, reason="root reads every folder")
def test_an_unreadable_folder_of_the_instructors_is_refused_not_left_behind(tmp_path):
    out = tmp_path / "out"
    write_run(out, {"a.txt": "1"})
    (out / "private").mkdir()
    (out / "private" / "grades.xlsx").write_text("x", encoding="utf-8")
    os.chmod(out / "private", 0)
    try:
        with pytest.raises(OutputError, match="cannot be read"):
            write_run(out, {"a.txt": "2"})
    finally:
        os.chmod(out / "private", 0o700)
    assert contents(out) == {"a.txt": "1", "private/grades.xlsx": "x"}
