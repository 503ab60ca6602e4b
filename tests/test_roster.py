"""read_roster: Canvas gradebook exports, Moodle grades exports and plain CSVs."""

from __future__ import annotations

from pathlib import Path

import pytest

from mechgrade.errors import AssignmentError
from mechgrade.roster import (MATCH_KINDS, MatchKind, Roster, RosterFormat, RosterStudent,
                              pair_students, read_roster)

DATA = Path(__file__).parent / "data" / "export"


def write(tmp_path: Path, text: str, *, encoding: str = "utf-8", name: str = "r.csv") -> Path:
    path = tmp_path / name
    path.write_bytes(text.encode(encoding))
    return path


def test_canvas_export_is_read_without_metadata_rows_and_test_student():
    roster = read_roster(DATA / "canvas_gradebook.csv")
    assert roster.format is RosterFormat.CANVAS
    assert roster.header[0] == "Student"  # the BOM is not part of the first column name
    assert roster.identity_header == ("Student", "ID", "SIS User ID", "SIS Login ID", "Section")
    assert [s.id for s in roster.students] == [f"7000{i}" for i in range(1, 8)]
    assert roster.skipped == ((11, "Canvas test student 'Student, Test'"),)
    ada = roster.students[0]
    assert (ada.name, ada.sis_user_id, ada.sis_login_id, ada.section, ada.email) == \
        ("Ada Lovelace", "s1001", "ada@uni.example", "ME 301-01", "ada@uni.example")
    assert ada.columns[0] == ("Student", "Lovelace, Ada")


def test_canvas_unicode_and_quoted_names_keep_their_original_cells():
    roster = read_roster(DATA / "canvas_gradebook.csv")
    by_id = {s.id: s for s in roster.students}
    assert by_id["70002"].name == "Émilie du Châtelet"
    assert by_id["70006"].columns[0] == ("Student", "O'Brien, Seán")
    assert by_id["70003"].columns[0][1] == '=HYPERLINK("http://evil.example","click")'


def test_moodle_export_is_read_with_email_and_id_number():
    roster = read_roster(DATA / "moodle_grades.csv")
    assert roster.format is RosterFormat.MOODLE
    assert roster.identity_header == ("First name", "Last name", "ID number", "Institution",
                                      "Department", "Email address")
    assert [s.id for s in roster.students] == ["s1001", "s1002", "s1003", "s1004",
                                               "uma@uni.example", "s1007"]
    assert roster.students[1].name == "Émilie du Châtelet"
    assert roster.students[4].email == "uma@uni.example"


def test_moodle_export_with_semicolons_is_read(tmp_path):
    path = write(tmp_path, "First name;Last name;ID number;Email address\n"
                           "Ada;Lovelace;s1;ada@x.org\n")
    roster = read_roster(path)
    assert roster.format is RosterFormat.MOODLE and roster.students[0].email == "ada@x.org"


def test_plain_roster_with_quotes_commas_and_bom(tmp_path):
    path = write(tmp_path, 'id,name,email\r\ns1,"Roe, ""Bo""",bo@x.org\r\n\r\ns2,Zoë,\r\n',
                 encoding="utf-8-sig")
    roster = read_roster(path)
    assert roster.format is RosterFormat.PLAIN
    assert [(s.id, s.name, s.email) for s in roster.students] == \
        [("s1", 'Roe, "Bo"', "bo@x.org"), ("s2", "Zoë", "")]


def test_plain_roster_fixture_is_read():
    roster = read_roster(DATA / "plain_roster.csv")
    assert len(roster.students) == 7 and roster.students[2].name == 'Mallory "Formula", Esq.'


@pytest.mark.parametrize("text, message", [
    ("", "r.csv:1: expected a roster header row, found an empty file"),
    ("\n\n", "r.csv:1: expected a roster header row, found an empty file"),
    ("a,b,c\n1,2,3\n", "r.csv:1: expected a roster header: a Canvas gradebook export (Student,"
                       "ID,SIS User ID,SIS Login ID,Section,...), a Moodle grades export (First "
                       "name,Last name,ID number,...,Email address) or a plain CSV (id,name"
                       "[,email]); found 'a,b,c'"),
    ("id,name\ns1,A\ns1,B\n",
     "r.csv:3: expected each student once, found id 's1' again (first on line 2)"),
    ("id,name\ns1,A,extra\n", "r.csv:2: expected at most 2 cells as in the header, found 3"),
    ("id,name\n,Nobody\n", "r.csv:2: column 'id': expected a student id, found an empty cell"),
    ("id,name,ID\n", "r.csv:1:3: expected distinct column names, found 'ID' twice"),
    ("id,name\ns1,\"A\"b\n", "r.csv:2: expected CSV cells, found bad quoting"),
    ("Student,ID,SIS User ID,SIS Login ID,Section\n\"Roe, Bo\",,s1,bo,A\n",
     "r.csv:2: column 'ID': expected a Canvas user ID for 'Roe, Bo', found an empty cell"),
    ("First name,Last name,ID number,Email address\nAda,Lovelace,,\n",
     "r.csv:2: expected an 'Email address' or 'ID number' to identify the student "
     "'Ada Lovelace', found both empty"),
])
def test_bad_roster_says_where_and_what_was_expected(tmp_path, text, message):
    path = write(tmp_path, text)
    with pytest.raises(AssignmentError) as err:
        read_roster(path)
    assert str(err.value).replace(str(tmp_path) + "/", "").startswith(message)


def test_roster_that_is_not_utf8_names_the_line(tmp_path):
    path = write(tmp_path, "id,name\ns1,Zo\u00eb\n", encoding="latin-1")
    with pytest.raises(AssignmentError, match=r"r\.csv:2: expected UTF-8 text .*found byte 0xeb"):
        read_roster(path)


def test_missing_roster_file_is_reported(tmp_path):
    with pytest.raises(AssignmentError, match=r"nope.csv: expected a roster CSV file, found no "
                                              "such file"):
        read_roster(tmp_path / "nope.csv")


def test_quoted_multiline_cell_keeps_line_numbers_right(tmp_path):
    path = write(tmp_path, 'id,name\ns1,"two\nlines"\ns1,again\n')
    with pytest.raises(AssignmentError, match=r"r\.csv:4: expected each student once"):
        read_roster(path)


ADA = RosterStudent("101", "Ada Lovelace", "ada@uni.edu", sis_login_id="ada")
BOB = RosterStudent("102", "Bob Roe", "bob@uni.edu", sis_login_id="bob")
TWO = Roster((ADA, BOB), RosterFormat.PLAIN, ("id", "name", "email"))


def folders(*names: str) -> list[dict[str, set[str]]]:
    """Folder names as candidates: a folder may be named by any identifier of a student."""
    from mechgrade.roster import fold

    return [{kind: {fold(name)} for kind in MATCH_KINDS if kind is not MatchKind.NAME}
            for name in names]


def test_each_student_is_paired_with_the_one_folder_that_names_them():
    pairing = pair_students(TWO, folders("ada", "102"))
    assert pairing.pairs == ((0, MatchKind.SIS_LOGIN_ID), (1, MatchKind.ID))
    assert pairing.conflicts == ()


def test_a_folder_named_with_another_students_id_is_a_conflict_not_a_winner():
    """'101' (Ada's LMS id) holding Bob's work used to win over Ada's own folder 'ada'."""
    pairing = pair_students(TWO, folders("101", "ada", "bob"))
    assert pairing.pairs == ((None, None), (2, MatchKind.SIS_LOGIN_ID))
    (conflict,) = pairing.conflicts
    assert (conflict.students, conflict.candidates) == ((0,), (0, 1))
    assert conflict.routes == ((0, 0, (MatchKind.ID,)),
                              (0, 1, (MatchKind.SIS_LOGIN_ID, MatchKind.EMAIL_USER)))
    assert conflict.describe(TWO, ["101", "ada", "bob"]) == (
        "'101' matches Ada Lovelace (101) by id; 'ada' matches Ada Lovelace (101) by SIS "
        "login id and email user name")


def test_two_folders_differing_in_letter_case_are_a_conflict_not_a_zero():
    pairing = pair_students(TWO, folders("ADA", "ada"))
    assert pairing.pairs == ((None, None), (None, None))
    assert [(c.students, c.candidates) for c in pairing.conflicts] == [((0,), (0, 1))]


def test_a_folder_matching_two_students_is_a_conflict():
    roster = Roster((ADA, RosterStudent("7", "Cy Doe", sis_user_id="101")), RosterFormat.PLAIN,
                    ("id", "name"))
    pairing = pair_students(roster, folders("101"))
    assert pairing.pairs == ((None, None), (None, None))
    (conflict,) = pairing.conflicts
    assert (conflict.students, conflict.candidates) == ((0, 1), (0,))
    assert conflict.describe(roster, ["101"]) == (
        "'101' matches Ada Lovelace (101) by id; '101' matches Cy Doe (7) by SIS user id")


def test_an_identifier_two_roster_students_share_identifies_neither():
    twins = Roster((RosterStudent("1", "Jo Smith"), RosterStudent("2", "Jo Smith")),
                   RosterFormat.PLAIN, ("id", "name"))
    results = [{MatchKind.ID: {"1"}, MatchKind.NAME: {"jo smith"}},
               {MatchKind.ID: {"2"}, MatchKind.NAME: {"jo smith"}}]
    pairing = pair_students(twins, results)
    assert pairing.pairs == ((0, MatchKind.ID), (1, MatchKind.ID))
    assert pairing.conflicts == ()
