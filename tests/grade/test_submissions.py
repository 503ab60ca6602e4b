"""Reading submission folders: every layout, and hostile or odd input that must not stop a run."""

from __future__ import annotations

import os

import pytest

from mechgrade.errors import SubmissionError
from mechgrade.grade import submissions as subs
from mechgrade.grade.results import SkippedEntry
from mechgrade.grade.submissions import read_answer_file, read_submissions

KEYS = frozenset({"p.speed", "p.angle", "q.acc"})


def student(root, name, keys=None):
    found = {s.student: s for s in read_submissions(root, keys=keys).students}
    return found[name]


def test_folder_with_answers_txt_reads_key_value_lines(tmp_path):
    (tmp_path / "ana").mkdir()
    (tmp_path / "ana" / "answers.txt").write_bytes(
        b"# my answers\r\n\r\np.speed = 7.10 m/s   # rounded\r\n  p.angle=30 deg\r\n")
    ana = student(tmp_path, "ana")
    assert ana.status == "read"
    assert ana.answers == (("p.angle", "30 deg"), ("p.speed", "7.10 m/s"))
    assert ana.messages == ()
    assert ana.files == ("ana/answers.txt",)


def test_yaml_answers_keep_numbers_as_typed_and_may_nest(tmp_path):
    (tmp_path / "ana").mkdir()
    (tmp_path / "ana" / "answers.yaml").write_text(
        "p:\n  speed: 7.10\n  angle: 30 deg\nq.acc: [-66.0, -40]  # a vector\n", encoding="utf-8")
    ana = student(tmp_path, "ana")
    assert ana.answers == (("p.angle", "30 deg"), ("p.speed", "7.10"), ("q.acc", "(-66.0, -40)"))


def test_json_answers_keep_numbers_as_typed(tmp_path):
    (tmp_path / "ana.json").write_text('{"p.speed": 7.10, "q": {"acc": "(-66, -40) ft/s^2"}}',
                                       encoding="utf-8")
    ana = student(tmp_path, "ana")
    assert ana.answers == (("p.speed", "7.10"), ("q.acc", "(-66, -40) ft/s^2"))


def test_one_file_per_student_in_the_folder(tmp_path):
    (tmp_path / "bo.txt").write_text("p.speed = 1 m/s\n", encoding="utf-8")
    (tmp_path / "cy.yaml").write_text("p.speed: 2 m/s\n", encoding="utf-8")
    (tmp_path / "di.yml").write_text("p.speed: 3 m/s\n", encoding="utf-8")
    found = read_submissions(tmp_path)
    assert [(s.student, s.answer("p.speed")) for s in found.students] == [
        ("bo", "1 m/s"), ("cy", "2 m/s"), ("di", "3 m/s")]


def test_students_are_sorted_by_id_whatever_the_listing_order(tmp_path):
    for name in ("zed", "amy", "Kim"):
        (tmp_path / f"{name}.txt").write_text("p.speed = 1 m/s\n", encoding="utf-8")
    assert [s.student for s in read_submissions(tmp_path).students] == ["Kim", "amy", "zed"]


def test_binary_file_makes_the_student_unreadable(tmp_path):
    (tmp_path / "ivy").mkdir()
    (tmp_path / "ivy" / "answers.txt").write_bytes(b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR")
    ivy = student(tmp_path, "ivy")
    assert ivy.status == "unreadable"
    assert ivy.answers == ()
    assert ivy.messages == ("'ivy/answers.txt' is a binary file, not text; expected answers "
                            "typed as text",)


def test_windows_1252_text_is_read_with_a_warning(tmp_path):
    (tmp_path / "gi.txt").write_bytes(b"p.speed = 98.5 ft/s\xb2\np.angle = \x9630 deg\n")
    gi = student(tmp_path, "gi")
    assert gi.status == "read"
    assert gi.answers == (("p.angle", "–30 deg"), ("p.speed", "98.5 ft/s²"))
    assert gi.messages == ("'gi.txt' is not UTF-8 (byte 0xb2 on line 1); it was read as "
                           "Windows-1252 text: check the answers as read back",)


def test_text_that_is_neither_utf8_nor_windows_1252_is_unreadable(tmp_path):
    (tmp_path / "gi.txt").write_bytes(b"p.speed = 1 m/s\np.angle = \x81\n")
    gi = student(tmp_path, "gi")
    assert gi.status == "unreadable"
    assert gi.messages == ("'gi.txt' is not UTF-8 text (byte 0x81 on line 2); save it as UTF-8",)


def test_utf16_with_byte_order_mark_is_read(tmp_path):
    (tmp_path / "ux.txt").write_bytes("p.speed = 7 m/s\n".encode("utf-16"))
    assert student(tmp_path, "ux").answers == (("p.speed", "7 m/s"),)


def test_utf8_byte_order_mark_is_dropped(tmp_path):
    (tmp_path / "bom.txt").write_bytes("\ufeffp.speed = 7 m/s\n".encode("utf-8"))
    assert student(tmp_path, "bom").answers == (("p.speed", "7 m/s"),)


def test_empty_folder_is_a_missing_submission(tmp_path):
    (tmp_path / "frank").mkdir()
    (tmp_path / "frank" / ".keep").write_text("", encoding="utf-8")
    frank = student(tmp_path, "frank")
    assert frank.status == "missing"
    assert frank.messages == ("the folder 'frank' is empty: no answers handed in",)


def test_empty_file_is_unreadable(tmp_path):
    (tmp_path / "em.txt").write_text("  \n", encoding="utf-8")
    em = student(tmp_path, "em")
    assert em.status == "unreadable"
    assert em.messages == ("'em.txt' is empty: no answers handed in",)


def test_file_with_only_comments_holds_no_answers(tmp_path):
    (tmp_path / "co.txt").write_text("# nothing yet\n", encoding="utf-8")
    assert student(tmp_path, "co").messages == (
        "'co.txt' holds no answers (expected lines such as 'problem_id.objective_id = 7.5 m/s')",)


def test_huge_file_is_refused_without_reading_it(tmp_path, monkeypatch):
    monkeypatch.setattr(subs, "MAX_FILE_BYTES", 100)
    (tmp_path / "big.txt").write_text("p.speed = " + "9" * 200 + "\n", encoding="utf-8")
    big = student(tmp_path, "big")
    assert big.status == "unreadable"
    assert big.messages == ("'big.txt' is 211 bytes; answer files may be at most 100 bytes",)


def test_link_to_a_folder_outside_is_not_followed(tmp_path):
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "answers.txt").write_text("p.speed = 1 m/s\n", encoding="utf-8")
    root = tmp_path / "subs"
    root.mkdir()
    os.symlink(outside, root / "mal")
    mal = student(root, "mal")
    assert mal.status == "unreadable"
    assert mal.answers == ()
    assert mal.messages == ("'mal' is a link to outside the submissions folder; it was not "
                            "followed",)


def test_link_to_a_file_outside_is_not_followed(tmp_path):
    secret = tmp_path / "secret.txt"
    secret.write_text("p.speed = 1 m/s\n", encoding="utf-8")
    root = tmp_path / "subs"
    (root / "mal").mkdir(parents=True)
    os.symlink(secret, root / "mal" / "answers.txt")
    os.symlink(secret, root / "eve.txt")
    assert student(root, "mal").messages == ("'mal/answers.txt' is a link to outside the "
                                             "submissions folder; it was not followed",)
    assert student(root, "eve").status == "unreadable"


def test_link_into_another_students_folder_is_flagged_not_read(tmp_path):
    (tmp_path / "ana").mkdir()
    (tmp_path / "ana" / "answers.txt").write_text("p.speed = 1 m/s\n", encoding="utf-8")
    os.symlink(tmp_path / "ana" / "answers.txt", tmp_path / "bob.txt")
    (tmp_path / "cy").mkdir()
    os.symlink(tmp_path / "ana" / "answers.txt", tmp_path / "cy" / "answers.txt")
    found = read_submissions(tmp_path)
    bob, cy = (s for s in found.students if s.student in ("bob", "cy"))
    shared = ("is a link to 'ana/answers.txt', inside another student's submission: it was "
              "not read (two students handing in the same work)")
    assert (bob.status, bob.answers, bob.messages) == ("unreadable", (), (f"'bob.txt' {shared}",))
    assert cy.messages == (f"'cy/answers.txt' {shared}",)
    assert found.notes == (f"'bob.txt' {shared}", f"'cy/answers.txt' {shared}")
    assert SkippedEntry("cy/answers.txt", shared) in found.skipped


def test_link_to_a_students_own_file_is_followed(tmp_path):
    (tmp_path / "ana").mkdir()
    (tmp_path / "ana" / "answers.txt").write_text("p.speed = 1 m/s\n", encoding="utf-8")
    os.symlink(tmp_path / "ana" / "answers.txt", tmp_path / "ana.txt")
    (ana,) = read_submissions(tmp_path).students
    assert ana.answers == (("p.speed", "1 m/s"),)


def test_dangling_links_are_skipped_with_their_target(tmp_path):
    os.symlink(tmp_path / "gone", tmp_path / "ana")
    (tmp_path / "bo").mkdir()
    os.symlink(tmp_path / "gone.txt", tmp_path / "bo" / "answers.txt")
    found = read_submissions(tmp_path)
    assert SkippedEntry("ana", f"a link to nothing ('{tmp_path}/gone')") in found.skipped
    (bo,) = found.students
    assert bo.status == "unreadable"
    assert bo.messages == (f"'bo/answers.txt' is a link to nothing ('{tmp_path}/gone.txt')",)


def test_a_fifo_is_not_opened(tmp_path):
    (tmp_path / "pi").mkdir()
    os.mkfifo(tmp_path / "pi" / "answers.txt")
    pi = student(tmp_path, "pi")
    assert pi.status == "unreadable"
    assert pi.messages == ("'pi/answers.txt' is not a regular file; it was not read",)


def test_repeated_key_in_text_keeps_the_later_answer_and_says_so(tmp_path):
    (tmp_path / "re.txt").write_text("p.speed = 1 m/s\np.speed = 2 m/s\n", encoding="utf-8")
    re_ = student(tmp_path, "re")
    assert re_.answers == (("p.speed", "2 m/s"),)
    assert re_.messages == ("re.txt:2: 'p.speed' is answered again (first on line 1); the later "
                            "answer was graded",)


def test_repeated_key_in_json_keeps_the_later_answer_and_says_so(tmp_path):
    (tmp_path / "re.json").write_text('{"p.speed": "1 m/s", "p.speed": "2 m/s"}',
                                      encoding="utf-8")
    re_ = student(tmp_path, "re")
    assert re_.answers == (("p.speed", "2 m/s"),)
    assert re_.messages == ("'re.json': 'p.speed' is given more than once; the last one was "
                            "graded",)


def test_repeated_key_in_yaml_makes_that_file_unreadable(tmp_path):
    (tmp_path / "re.yaml").write_text("p.speed: 1 m/s\np.speed: 2 m/s\n", encoding="utf-8")
    re_ = student(tmp_path, "re")
    assert re_.status == "unreadable"
    assert re_.messages == ("re.yaml:2:1: p.speed: expected each key once, found 'p.speed' "
                            "again",)


def test_invalid_json_and_yaml_say_where(tmp_path):
    (tmp_path / "js.json").write_text('{"p.speed": "1 m/s",,}', encoding="utf-8")
    (tmp_path / "ya.yaml").write_text("p.speed: [1\n", encoding="utf-8")
    (tmp_path / "li.yaml").write_text("- 1\n- 2\n", encoding="utf-8")
    assert student(tmp_path, "js").messages == (
        "js.json:1:21: expected valid JSON, found a syntax error (Expecting property name "
        "enclosed in double quotes)",)
    assert student(tmp_path, "ya").messages[0].startswith(
        "ya.yaml:1:10: unclosed '[': expected ',' or ']' after an item, found the end of the file")
    assert student(tmp_path, "li").messages == (
        "'li.yaml': expected answers keyed by 'problem_id.objective_id', found a list",)


def test_deeply_nested_json_is_refused(tmp_path):
    (tmp_path / "dn.json").write_text("[" * 100000 + "]" * 100000, encoding="utf-8")
    assert student(tmp_path, "dn").status == "unreadable"


def test_answer_that_is_a_mapping_is_reported(tmp_path):
    (tmp_path / "mp.yaml").write_text("p:\n  speed:\n    value: 7\n", encoding="utf-8")
    mp = student(tmp_path, "mp")
    assert mp.messages[0] == ("'mp.yaml': the answer to 'p.speed' is a mapping, expected text; "
                              "it was not read")


def test_unknown_keys_are_reported_never_dropped_silently(tmp_path):
    (tmp_path / "un.txt").write_text("p.speed = 1 m/s\np.sped = 2 m/s\nP.Angle = 3 deg\n",
                                     encoding="utf-8")
    un = student(tmp_path, "un", keys=KEYS)
    assert un.answers == (("p.angle", "3 deg"), ("p.speed", "1 m/s"))
    assert un.messages == (
        "read the key 'P.Angle' as 'p.angle'",
        "'p.sped' (un.txt) is not a question of this assignment; it was not graded")


def test_line_without_equals_sign_is_reported(tmp_path):
    (tmp_path / "ln.txt").write_text("p.speed = 1 m/s\nthe answer is 42\n= 5\n",
                                     encoding="utf-8")
    ln = student(tmp_path, "ln")
    assert ln.answers == (("p.speed", "1 m/s"),)
    assert ln.messages == (
        "ln.txt:2: expected 'problem_id.objective_id = answer', found 'the answer is 42'; the "
        "line was not read",
        "ln.txt:3: expected a key before '=', found none; the line was not read")


def test_two_files_for_one_student_are_combined_first_file_wins_conflicts(tmp_path):
    (tmp_path / "hal").mkdir()
    (tmp_path / "hal" / "answers.txt").write_text("p.speed = 1 m/s\np.angle = 3 deg\n",
                                                  encoding="utf-8")
    (tmp_path / "hal" / "answers.json").write_text('{"p.speed": "2 m/s"}', encoding="utf-8")
    (tmp_path / "hal.yaml").write_text("q.acc: 4 m/s^2\n", encoding="utf-8")
    hal = student(tmp_path, "hal")
    assert hal.answers == (("p.angle", "3 deg"), ("p.speed", "2 m/s"), ("q.acc", "4 m/s^2"))
    assert hal.files == ("hal/answers.json", "hal/answers.txt", "hal.yaml")
    assert hal.messages == (
        "'p.speed' is answered in both 'hal/answers.json' and 'hal/answers.txt'; the answer in "
        "'hal/answers.json' was graded",
        "answers were read from 3 files (hal/answers.json, hal/answers.txt, hal.yaml) and "
        "combined")


def test_one_readable_file_is_enough_to_be_read(tmp_path):
    (tmp_path / "mix").mkdir()
    (tmp_path / "mix" / "answers.txt").write_bytes(b"\x00\x01")
    (tmp_path / "mix" / "answers.json").write_text('{"p.speed": "2 m/s"}', encoding="utf-8")
    mix = student(tmp_path, "mix")
    assert mix.status == "read"
    assert mix.messages == ("'mix/answers.txt' is a binary file, not text; expected answers "
                            "typed as text",)


def test_other_files_in_a_student_folder_are_reported(tmp_path):
    (tmp_path / "ana").mkdir()
    (tmp_path / "ana" / "answers.txt").write_text("p.speed = 1 m/s\n", encoding="utf-8")
    (tmp_path / "ana" / "work.pdf").write_bytes(b"%PDF")
    (tmp_path / "ana" / "sub").mkdir()
    assert student(tmp_path, "ana").messages == (
        "ignored 'ana/sub', 'ana/work.pdf': answers go in answers.yaml, answers.json or "
        "answers.txt",)


def test_folder_with_only_other_files_is_missing_with_a_message(tmp_path):
    (tmp_path / "ana").mkdir()
    (tmp_path / "ana" / "hw.docx").write_bytes(b"PK")
    ana = student(tmp_path, "ana")
    assert ana.status == "missing"
    assert ana.messages == ("ignored 'ana/hw.docx': answers go in answers.yaml, answers.json "
                            "or answers.txt",)


def test_every_entry_not_read_is_listed_as_skipped_with_its_reason(tmp_path):
    (tmp_path / "README.md").write_text("hi", encoding="utf-8")
    (tmp_path / ".DS_Store").write_bytes(b"\x00")
    (tmp_path / "__MACOSX").mkdir()
    (tmp_path / ".hidden").mkdir()
    os.mkfifo(tmp_path / "pipe")
    (tmp_path / "ana").mkdir()
    (tmp_path / "ana" / "answers.txt").write_text("p.speed = 1 m/s\n", encoding="utf-8")
    (tmp_path / "ana" / ".DS_Store").write_bytes(b"\x00")
    (tmp_path / "ana" / "work.pdf").write_bytes(b"%PDF")
    found = read_submissions(tmp_path)
    assert [s.student for s in found.students] == ["ana"]
    assert found.skipped == (
        SkippedEntry(".DS_Store", "hidden (its name starts with '.')"),
        SkippedEntry(".hidden", "hidden (its name starts with '.')"),
        SkippedEntry("README.md", subs.NOT_A_SUBMISSION),
        SkippedEntry("__MACOSX", "made by macOS when zipping, not a submission"),
        SkippedEntry("ana/.DS_Store", "hidden (its name starts with '.')"),
        SkippedEntry("ana/work.pdf", subs.NOT_AN_ANSWER_FILE),
        SkippedEntry("pipe", "not a file or folder (a FIFO)"),
    )


def test_names_are_kept_byte_for_byte(tmp_path):
    for name in ("Zo\u00eb", "Zoe\u0308", " ana", "ana"):
        (tmp_path / f"{name}.txt").write_text("p.speed = 1 m/s\n", encoding="utf-8")
    os.mkdir(os.path.join(os.fsencode(tmp_path), b"bad\xe9name"))
    found = read_submissions(tmp_path)
    assert sorted(s.student for s in found.students) == sorted(
        [" ana", "ana", "Zo\u00eb", "Zoe\u0308", "bad\\xe9name"])
    assert found.notes == (
        "2 folders whose names differ only in letter case, spaces or Unicode form: ' ana' "
        "( ana), 'ana' (ana); graded as 2 different students",
        "2 folders whose names differ only in Unicode form: 'Zoe\u0308' (Zoe\\u0308), "
        "'Zo\u00eb' (Zo\\xeb); graded as 2 different students")


def test_answers_file_in_another_letter_case_is_read_and_named(tmp_path):
    (tmp_path / "ana").mkdir()
    (tmp_path / "ana" / "Answers.YAML").write_text("p.speed: 1 m/s\n", encoding="utf-8")
    (tmp_path / "ana" / "answers.yaml").write_text("p.angle: 2 deg\n", encoding="utf-8")
    (ana,) = read_submissions(tmp_path).students
    assert ana.answers == (("p.angle", "2 deg"), ("p.speed", "1 m/s"))
    assert "read 'ana/Answers.YAML' as the answers file" in ana.messages


def test_a_fault_while_reading_one_student_makes_only_that_student_unreadable(tmp_path,
                                                                              monkeypatch):
    for name in ("ana", "bo"):
        (tmp_path / f"{name}.txt").write_text("p.speed = 1 m/s\n", encoding="utf-8")
    real = subs.read_answer_file

    def broken(path, *, label=None):
        if label == "bo.txt":
            raise ZeroDivisionError("division by zero")
        return real(path, label=label)

    monkeypatch.setattr(subs, "read_answer_file", broken)
    ana, bo = read_submissions(tmp_path).students
    assert ana.status == "read"
    assert (bo.status, bo.internal_error) == ("unreadable",
                                              "reading 'bo': ZeroDivisionError: division by zero")
    assert bo.messages == ("internal error while reading this submission: ZeroDivisionError: "
                           "division by zero; please tell your instructor",)


def test_lone_surrogates_in_json_answers_are_escaped_visibly(tmp_path):
    (tmp_path / "ana.json").write_text('{"p.speed": "7\\ud800 m/s"}', encoding="utf-8")
    (ana,) = read_submissions(tmp_path).students
    assert ana.answers == (("p.speed", "7\\ud800 m/s"),)


def test_long_answers_are_kept_whole_and_many_unknown_keys_summarised(tmp_path):
    long = "1" * 100_000
    (tmp_path / "lo.txt").write_text("".join(f"k{i:02d} = {i}\n" for i in range(12))
                                     + f"p.speed = {long}\n", encoding="utf-8")
    lo = student(tmp_path, "lo", keys=KEYS)
    assert lo.answers == (("p.speed", long),)
    assert lo.messages[-2:] == ("'k09' (lo.txt) is not a question of this assignment; it was "
                                "not graded", "2 more keys are not questions of this "
                                "assignment; they were not graded")


def test_utf32_with_byte_order_mark_is_read(tmp_path):
    (tmp_path / "u.txt").write_bytes("p.speed = 1 m/s\n".encode("utf-32"))
    assert student(tmp_path, "u").answers == (("p.speed", "1 m/s"),)


def test_a_key_answered_flat_and_nested_says_which_was_graded(tmp_path):
    (tmp_path / "n.json").write_text('{"p.speed": "1", "p": {"speed": "2"}}', encoding="utf-8")
    n = student(tmp_path, "n")
    assert n.answers == (("p.speed", "2"),)
    assert n.messages == ("'n.json': 'p.speed' is answered twice (flat and nested); the later "
                          "answer was graded",)


def test_control_characters_in_keys_are_made_visible(tmp_path):
    (tmp_path / "cc.txt").write_text("p.spe\x1bed = 1\n", encoding="utf-8")
    assert student(tmp_path, "cc").answers == (("p.spe\ufffded", "1"),)


def test_missing_submissions_folder_is_an_error(tmp_path):
    with pytest.raises(SubmissionError) as info:
        read_submissions(tmp_path / "nope")
    assert str(info.value) == f"expected a folder of submissions, found nothing at " \
                              f"'{tmp_path / 'nope'}'"


def test_read_answer_file_refuses_a_file_with_nothing_readable(tmp_path):
    path = tmp_path / "x.txt"
    path.write_text("no equals here\n", encoding="utf-8")
    with pytest.raises(SubmissionError, match="holds no answers"):
        read_answer_file(path)


# What a file repeats many times is listed at most MAX_LISTED_KEYS times and summarised, as
# unknown keys are: one message per repeat made a 256 KiB file 1.2 MB of results.
LISTED = subs.MAX_LISTED_KEYS


def _capped(messages, listed_start: str, summary: str) -> None:
    assert sum(m.startswith(listed_start) and m != summary for m in messages) == LISTED, \
        messages[:3]
    assert summary in messages


def test_a_key_repeated_thousands_of_times_is_summarised(tmp_path):
    (tmp_path / "ann.txt").write_text("p.speed = 1 m/s\n" * 5000, encoding="utf-8")
    ann = student(tmp_path, "ann", KEYS)
    assert ann.answers == (("p.speed", "1 m/s"),)
    _capped(ann.messages, "ann.txt:", "ann.txt: 4989 more lines answer a key again; the "
                                      "latest answer to each was graded")
    assert len(ann.messages) == LISTED + 1


def test_thousands_of_unreadable_lines_are_summarised(tmp_path):
    (tmp_path / "bob.txt").write_text("p.speed = 1 m/s\n" + "garbage\n" * 5000 + "= 3\n",
                                      encoding="utf-8")
    bob = student(tmp_path, "bob", KEYS)
    _capped(bob.messages, "bob.txt:", "bob.txt: 4991 more lines were not read (expected "
                                      "'problem_id.objective_id = answer')")
    assert len(bob.messages) == LISTED + 1


def test_thousands_of_keys_repeated_in_json_are_summarised(tmp_path):
    pairs = ",".join(f'"k{i}": 1, "k{i}": 2' for i in range(3000))
    (tmp_path / "eve.json").write_text("{" + pairs + ', "p.speed": "1 m/s"}', encoding="utf-8")
    eve = student(tmp_path, "eve", KEYS)
    _capped(eve.messages, "'eve.json': 'k", "'eve.json': 2990 more keys are given more than "
                                            "once; the last of each was graded")


def test_thousands_of_answers_that_are_not_text_are_summarised(tmp_path):
    pairs = ",".join(f'"p.k{i}": [[1]]' for i in range(3000))
    (tmp_path / "eve.json").write_text("{" + pairs + ', "p.speed": "1 m/s"}', encoding="utf-8")
    eve = student(tmp_path, "eve", KEYS)
    _capped(eve.messages, "'eve.json': the answer to", "'eve.json': 2990 more answers are "
                                                      "not text; they were not read")


def test_thousands_of_stray_files_in_a_students_folder_are_summarised(tmp_path):
    (tmp_path / "dora").mkdir()
    (tmp_path / "dora" / "answers.txt").write_text("p.speed = 1 m/s\n", encoding="utf-8")
    for i in range(3000):
        (tmp_path / "dora" / f"scan{i:04d}.pdf").write_bytes(b"")
    found = read_submissions(tmp_path, keys=KEYS)
    (dora,) = found.students
    (message,) = dora.messages
    assert message.startswith("ignored 'dora/scan0000.pdf', 'dora/scan0001.pdf'")
    assert message.endswith("'dora/scan0009.pdf' and 2990 more files: answers go in "
                            "answers.yaml, answers.json or answers.txt")
    assert len(found.skipped) == LISTED + 1
    assert found.skipped[0] == SkippedEntry("dora/", "2990 more entries of this folder are not "
                                                     "answers files (not listed one by one)")
