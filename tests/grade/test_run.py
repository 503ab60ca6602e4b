"""The grading run: points, statuses, roster, order, error carried forward, the example class."""

from __future__ import annotations

import textwrap
from dataclasses import replace
from pathlib import Path

import pytest

from mechgrade.errors import (AssignmentError, InconsistentError, MechgradeError, SolveError,
                             SubmissionError)
from mechgrade.grade.assignment import load_assignment
from mechgrade.grade import run as run_module
from mechgrade.grade.ecf import CarriedForward, given_key_of
from mechgrade.grade.run import (expected_in_unit, expected_text, grade_plan,
                                 grade_submissions, plan_assignment)
from mechgrade.grade.sandbox import SandboxPool
from mechgrade.grade.submissions import read_submissions
from mechgrade.resources import shipped_dir
from mechgrade.roster import read_roster
from mechgrade.solve.result import ObjectiveResult, Solution
from mechgrade.spec import load_problem, load_problem_text

PROBLEMS = shipped_dir("problems")
PENDULUM = PROBLEMS / "bowling_3_15_4_pendulum.yaml"
BLOCKS = PROBLEMS / "bowling_3_15_8_connected_blocks.yaml"
EXAMPLE = shipped_dir("examples") / "hw1"

# The pendulum's reference answers, written by hand so these tests do not need the solver.
PENDULUM_SOLUTION = Solution("bowling_3_15_4_pendulum", (
    ObjectiveResult("acc_mag", "scalar", "ft/s^2", 98.5089),
    ObjectiveResult("acc_N", "vector", "ft/s^2", (-89.8705, -40.3397, 0.0), frame="N"),
    ObjectiveResult("acc_A", "vector", "ft/s^2", (-98.0, 10.0, 0.0), frame="A"),
    ObjectiveResult("acc_mag_symbolic", "symbolic", "ft/s^2", expr="L*sqrt(thetad**4 + thetadd**2)",
                    symbols=("L", "thetad", "thetadd"),
                    symbol_units=("m", "rad/s", "rad/s^2")),
))


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(textwrap.dedent(text), encoding="utf-8")
    return path


@pytest.fixture
def class_dir(tmp_path):
    """An assignment on the pendulum problem (its file named by its id, so it has no warning)
    and a folder of three submissions."""
    write(tmp_path / PENDULUM.name, PENDULUM.read_text(encoding="utf-8"))
    write(tmp_path / "hw.yaml", """\
        id: hw9
        title: Pendulum
        problems:
          - path: bowling_3_15_4_pendulum.yaml
            objectives: [acc_mag, acc_N]
        points: {default: 2, bowling_3_15_4_pendulum.acc_N: 4}
        policy:
          partial_credit: {diagnoses: {sign: 0.5, swapped: 0.25}}
        """)
    subs = tmp_path / "subs"
    write(subs / "ann" / "answers.txt", """\
        bowling_3_15_4_pendulum.acc_mag = 98.5 ft/s^2
        bowling_3_15_4_pendulum.acc_N = (-89.9, -40.3) ft/s^2
        """)
    write(subs / "ben.txt", """\
        bowling_3_15_4_pendulum.acc_mag = -98.5 ft/s^2
        bowling_3_15_4_pendulum.acc_N = (-40.3, -89.9) ft/s^2
        """)
    (subs / "cat.txt").write_bytes(b"\x00\x01binary")
    return tmp_path


def pendulum_plan(folder: Path):
    hw = load_assignment(folder / "hw.yaml")
    problem = load_problem(folder / PENDULUM.name)
    return plan_assignment(hw, problems=[problem], solutions=[PENDULUM_SOLUTION])


def grade(folder: Path, roster=None, **kwargs):
    plan = pendulum_plan(folder)
    return grade_plan(plan, read_submissions(folder / "subs", keys=plan.keys), roster, **kwargs)


def test_points_are_credit_times_objective_points_and_totals_add_up(class_dir):
    report = grade(class_dir)
    assert [(o.objective, o.max_points) for o in report.objectives] == [("acc_mag", 2.0),
                                                                         ("acc_N", 4.0)]
    by_id = {s.id: s for s in report.students}
    ann, ben = by_id["ann"], by_id["ben"]
    assert [(a.verdict, a.points) for a in ann.answers] == [("correct", 2.0), ("correct", 4.0)]
    assert (ann.status, ann.score, ann.max_score) == ("graded", 6.0, 6.0)
    assert [(a.verdict, a.points, a.diagnosis) for a in ben.answers] == [
        ("partial", 1.0, "sign error"), ("partial", 1.0, "swapped components")]
    assert ben.score == 2.0


def test_unreadable_submission_has_status_and_verdicts_unreadable(class_dir):
    cat = {s.id: s for s in grade(class_dir).students}["cat"]
    assert (cat.status, cat.score) == ("unreadable", 0.0)
    assert {a.verdict for a in cat.answers} == {"unreadable"}
    assert cat.messages == ("'cat.txt' is a binary file, not text; expected answers typed as "
                            "text",)


def test_answer_left_out_is_missing_with_no_points(class_dir):
    write(class_dir / "subs" / "dee.txt", "bowling_3_15_4_pendulum.acc_mag = 98.5 ft/s^2\n")
    dee = {s.id: s for s in grade(class_dir).students}["dee"]
    assert [(a.verdict, a.points, a.answer) for a in dee.answers] == [
        ("correct", 2.0, "98.5 ft/s^2"), ("missing", 0.0, None)]


def test_every_roster_student_appears_in_roster_order_then_others(class_dir):
    roster_path = write(class_dir / "roster.csv", """\
        id,name,email
        ben,Ben Bo,ben@uni.edu
        zoe,Zoe Zed,zoe@uni.edu
        s-ann,Ann Ash,ann@uni.edu
        """)
    report = grade(class_dir, read_roster(roster_path))
    assert [(s.id, s.name, s.status) for s in report.students] == [
        ("ben", "Ben Bo", "graded"), ("zoe", "Zoe Zed", "missing"),
        ("ann", "Ann Ash", "graded"), ("cat", "", "unreadable")]
    zoe = report.students[1]
    assert zoe.messages == ("no submission found",)
    assert {a.verdict for a in zoe.answers} == {"missing"} and zoe.score == 0.0
    assert report.students[3].messages[0] == "not on the roster"
    assert dict(report.students[0].identity)["email"] == "ben@uni.edu"


def test_a_folder_named_with_another_students_id_is_a_conflict_not_a_grade(class_dir):
    """'s-ann' (Ann's roster id) holding Ben's work used to win over Ann's own folder 'ann';
    now neither is Ann's, and both are listed with the conflict."""
    write(class_dir / "subs" / "s-ann.txt", "bowling_3_15_4_pendulum.acc_mag = 98.5 ft/s^2\n")
    roster_path = write(class_dir / "roster.csv", """\
        id,name,email
        ben,Ben Bo,ben@uni.edu
        s-ann,Ann Ash,ann@uni.edu
        """)
    report = grade(class_dir, read_roster(roster_path))
    said = "'ann' matches Ann Ash (s-ann) by email user name; 's-ann' matches Ann Ash (s-ann) by id"
    assert [(s.id, s.name, s.status) for s in report.students] == [
        ("ben", "Ben Bo", "graded"), ("s-ann", "Ann Ash", "conflict"), ("ann", "", "conflict"),
        ("cat", "", "unreadable"), ("s-ann", "", "conflict")]
    ann = report.students[1]
    assert ann.messages == (f"roster conflict: {said}; graded as no one's until your "
                            f"instructor sorts it out",)
    assert dict(ann.identity)["id"] == "s-ann"
    assert report.students[2].score == 6.0  # graded, as no one's
    assert report.notes == (f"roster conflict: {said}; none of these folders was graded as "
                            f"anyone's (status 'conflict', kept out of exports): rename the "
                            f"folders so that each matches one student",)


def test_two_folders_differing_in_letter_case_are_a_conflict_not_a_zero(class_dir):
    write(class_dir / "subs" / "ANN.txt", "bowling_3_15_4_pendulum.acc_mag = 1 ft/s^2\n")
    roster_path = write(class_dir / "roster.csv", "id,name\nann,Ann Ash\n")
    report = grade(class_dir, read_roster(roster_path))
    assert [(s.id, s.status) for s in report.students] == [
        ("ann", "conflict"), ("ANN", "conflict"), ("ann", "conflict"), ("ben", "graded"),
        ("cat", "unreadable")]
    assert report.notes[-1].startswith("roster conflict: 'ANN' matches Ann Ash (ann) by id; "
                                       "'ann' matches Ann Ash (ann) by id;")


def test_without_roster_students_are_sorted_by_id(class_dir):
    assert [s.id for s in grade(class_dir).students] == ["ann", "ben", "cat"]


def test_grading_twice_gives_equal_reports(class_dir):
    assert grade(class_dir) == grade(class_dir)


def test_progress_is_reported_for_every_student(class_dir):
    calls = []
    grade(class_dir, progress=lambda done, total: calls.append((done, total)))
    assert calls == [(0, 3), (1, 3), (2, 3), (3, 3)]


def test_expected_answers_are_shown_only_when_revealed(class_dir):
    assert {a.expected for s in grade(class_dir).students for a in s.answers} == {None}
    text = (class_dir / "hw.yaml").read_text(encoding="utf-8")
    (class_dir / "hw.yaml").write_text(text.replace("policy:\n", "policy:\n  reveal_answers: true\n"),
                                       encoding="utf-8")
    ann = grade(class_dir).students[0]
    assert [a.expected for a in ann.answers] == ["98.51 ft/s^2", "(-89.87, -40.34, 0) ft/s^2 in frame N"]


def test_expected_answers_are_also_given_in_the_unit_the_student_wrote(class_dir):
    text = (class_dir / "hw.yaml").read_text(encoding="utf-8")
    (class_dir / "hw.yaml").write_text(text.replace("policy:\n", "policy:\n  reveal_answers: true\n"),
                                       encoding="utf-8")
    write(class_dir / "subs" / "ann" / "answers.txt", """\
        bowling_3_15_4_pendulum.acc_mag = 30.03 m/s^2
        bowling_3_15_4_pendulum.acc_N = (-89.9, -40.3) ft/s^2
        """)
    by_id = {s.id: s for s in grade(class_dir).students}
    assert [(a.expected, a.expected_in_answer_unit) for a in by_id["ann"].answers] == [
        ("98.51 ft/s^2", "30.03 m/s^2"),
        ("(-89.87, -40.34, 0) ft/s^2 in frame N", None)]  # written in the objective's unit
    assert {a.expected_in_answer_unit for a in by_id["cat"].answers} == {None}  # unreadable
    hidden = (class_dir / "hw.yaml").read_text(encoding="utf-8").replace("  reveal_answers: true\n", "")
    (class_dir / "hw.yaml").write_text(hidden, encoding="utf-8")
    assert {a.expected_in_answer_unit for s in grade(class_dir).students for a in s.answers} == {None}


def test_assignment_policy_reaches_the_judge(class_dir):
    text = (class_dir / "hw.yaml").read_text(encoding="utf-8")
    (class_dir / "hw.yaml").write_text(text.replace("policy:\n", "policy:\n  tolerance: {rel: 0.1}\n"),
                                       encoding="utf-8")
    write(class_dir / "subs" / "ann" / "answers.txt",
          "bowling_3_15_4_pendulum.acc_mag = 93 ft/s^2\n")
    assert grade(class_dir).students[0].answers[0].verdict == "correct"


def test_unknown_objective_in_assignment_says_where(class_dir):
    text = (class_dir / "hw.yaml").read_text(encoding="utf-8")
    (class_dir / "hw.yaml").write_text(text.replace("[acc_mag, acc_N]", "[acc_mag, acc_X]"),
                                       encoding="utf-8")
    with pytest.raises(AssignmentError) as info:
        pendulum_plan(class_dir)
    assert str(info.value) == (
        f"{class_dir / 'hw.yaml'}:4:11: problems[0].path: expected an objective of problem "
        f"'bowling_3_15_4_pendulum' (acc_mag, acc_N, acc_A, acc_mag_symbolic), found 'acc_X'")


def test_points_for_an_objective_not_graded_says_where(class_dir):
    text = (class_dir / "hw.yaml").read_text(encoding="utf-8")
    (class_dir / "hw.yaml").write_text(text.replace("acc_N: 4}", "acc_A: 4}"), encoding="utf-8")
    with pytest.raises(AssignmentError) as info:
        pendulum_plan(class_dir)
    assert str(info.value) == (
        f"{class_dir / 'hw.yaml'}:6:53: points.bowling_3_15_4_pendulum.acc_A: expected a graded "
        f"objective 'problem_id.objective_id' (bowling_3_15_4_pendulum.acc_N, "
        f"bowling_3_15_4_pendulum.acc_mag), found 'bowling_3_15_4_pendulum.acc_A'")


def test_two_problem_files_with_one_id_are_refused(class_dir):
    write(class_dir / "copy.yaml", PENDULUM.read_text(encoding="utf-8"))
    write(class_dir / "hw.yaml", """\
        id: hw9
        title: Pendulum
        problems: [bowling_3_15_4_pendulum.yaml, copy.yaml]
        """)
    hw = load_assignment(class_dir / "hw.yaml")
    problem = load_problem(PENDULUM)
    with pytest.raises(AssignmentError) as info:
        plan_assignment(hw, problems=[problem, problem],
                        solutions=[PENDULUM_SOLUTION, PENDULUM_SOLUTION])
    assert str(info.value).endswith(
        "hw.yaml:3:42: problems[1]: expected problems with different ids, found "
        "'bowling_3_15_4_pendulum' twice")


def test_expected_text_formats_each_kind():
    assert expected_text(ObjectiveResult("a", "scalar", "m / s", 0.0)) == "0 m/s"
    assert expected_text(ObjectiveResult("a", "symbolic", "m", expr="L*x")) == "L*x m"
    assert expected_text(ObjectiveResult("a", "symbolic", "", expr=None)) == "(no reference)"
    assert expected_text(ObjectiveResult("a", "vector", "", (1.0, 2.0, 3.0))) == "(1, 2, 3)"


def test_expected_in_the_students_unit_keeps_the_figures_of_the_expected_text():
    speed = ObjectiveResult("w", "scalar", "rad/s", -4.3354)
    assert expected_text(speed) == "-4.335 rad/s"
    assert expected_in_unit(speed, "rpm") == "-41.4 rpm"
    assert expected_in_unit(speed, "deg / s") == "-248.4 deg/s"
    force = ObjectiveResult("F", "vector", "N", (36.787, 0.0, -1.0), frame="B")
    assert expected_in_unit(force, "lbf") == "(8.27, 0, -0.2248) lbf"


def test_expected_in_the_students_unit_is_nothing_when_it_would_say_nothing_more():
    force = ObjectiveResult("F", "scalar", "N", 36.787)
    assert expected_in_unit(force, "N") is None
    assert expected_in_unit(force, "kg * m / s ** 2") is None  # the same numbers
    assert expected_in_unit(force, "m") is None  # another dimension
    assert expected_in_unit(force, "furlongs_of_doom") is None  # not a unit mechgrade reads
    assert expected_in_unit(ObjectiveResult("a", "symbolic", "m", expr="L*x"), "ft") is None
    assert expected_in_unit(ObjectiveResult("a", "scalar", "m", None), "ft") is None


# ---------------------------------------------------------------------------- ECF

ECF_ASSIGNMENT = """\
    id: ecf
    title: Connected blocks
    problems:
      - path: blocks.yaml
        objectives: [xdot, rod_omega_z, P_ZA_frameA]
    policy:
      ecf: {credit: %s}
    """


@pytest.fixture(scope="module")
def blocks_text():
    text = BLOCKS.read_text(encoding="utf-8")
    assert "  - id: rod_omega_z\n" in text
    return text


def ecf_class(tmp_path, spec_text, answers: dict[str, str], credit="1.0"):
    write(tmp_path / "blocks.yaml", spec_text)
    write(tmp_path / "hw.yaml", ECF_ASSIGNMENT % credit)
    for sid, text in answers.items():
        write(tmp_path / "subs" / f"{sid}.txt", text)
    return load_assignment(tmp_path / "hw.yaml")


def with_dependency(text: str, objective: str, upstream: str) -> str:
    """The problem text with ``objective`` depending on ``upstream`` (added if not declared)."""
    block = text.split(f"  - id: {objective}\n", 1)[1].split("  - id:", 1)[0]
    if f"depends_on: [{upstream}]" in block:
        return text
    return text.replace(f"  - id: {objective}\n",
                        f"  - id: {objective}\n    depends_on: [{upstream}]\n")


def answers_of(report, sid):
    return {a.objective: a for s in report.students if s.id == sid for a in s.answers}


def test_ecf_gives_credit_for_an_answer_that_follows_from_a_wrong_upstream(tmp_path,
                                                                           blocks_text):
    hw = ecf_class(tmp_path, with_dependency(blocks_text, "rod_omega_z", "xdot"), {
        "hal": "bowling_3_15_8_connected_blocks.xdot = -7.00 m/s\n"
               "bowling_3_15_8_connected_blocks.rod_omega_z = 66.97 rad/s\n",
        "ida": "bowling_3_15_8_connected_blocks.xdot = -7.00 m/s\n"
               "bowling_3_15_8_connected_blocks.rod_omega_z = 50 rad/s\n",
        "jo": "bowling_3_15_8_connected_blocks.xdot = -7.67 m/s\n"
              "bowling_3_15_8_connected_blocks.rod_omega_z = 73.3 rad/s\n"})
    report = grade_submissions(hw, tmp_path / "subs")
    hal = answers_of(report, "hal")
    assert (hal["xdot"].verdict, hal["xdot"].points) == ("incorrect", 0.0)
    assert (hal["rod_omega_z"].verdict, hal["rod_omega_z"].points) == ("correct", 1.0)
    assert hal["rod_omega_z"].feedback == (
        "Error carried forward: this answer follows correctly from your answer to xdot (used in "
        "place of the given y') and earns 100% of the points.")
    ida = answers_of(report, "ida")
    assert (ida["rod_omega_z"].verdict, ida["rod_omega_z"].points) == ("incorrect", 0.0)
    assert ida["rod_omega_z"].feedback.endswith(
        "Also checked with your own answer to xdot (error carried forward): it does not follow "
        "from it either.")
    jo = answers_of(report, "jo")
    assert [jo[k].verdict for k in ("xdot", "rod_omega_z")] == ["correct", "correct"]
    assert "carried forward" not in jo["rod_omega_z"].feedback


def test_ecf_credit_is_the_assignment_share(tmp_path, blocks_text):
    hw = ecf_class(tmp_path, with_dependency(blocks_text, "rod_omega_z", "xdot"), {
        "hal": "bowling_3_15_8_connected_blocks.xdot = -7.00 m/s\n"
               "bowling_3_15_8_connected_blocks.rod_omega_z = 66.97 rad/s\n"}, credit="0.5")
    hal = answers_of(grade_submissions(hw, tmp_path / "subs"), "hal")
    assert (hal["rod_omega_z"].verdict, hal["rod_omega_z"].points) == ("partial", 0.5)


def test_ecf_is_not_faked_when_upstream_is_not_a_given_quantity(tmp_path, blocks_text):
    hw = ecf_class(tmp_path, with_dependency(blocks_text, "P_ZA_frameA", "rod_omega_z"), {
        "kim": "bowling_3_15_8_connected_blocks.rod_omega_z = 60 rad/s\n"
               "bowling_3_15_8_connected_blocks.P_ZA_frameA = (-0.2, 0) m\n"})
    kim = answers_of(grade_submissions(hw, tmp_path / "subs"), "kim")
    assert kim["P_ZA_frameA"].verdict == "incorrect"
    assert kim["P_ZA_frameA"].feedback.endswith(
        "Error carried forward could not be applied: 'rod_omega_z' is not a plain given "
        "quantity the solver can take from your answer.")


def test_ecf_reports_a_problem_that_cannot_be_solved_with_the_student_value(tmp_path,
                                                                            blocks_text):
    hw = ecf_class(tmp_path, with_dependency(blocks_text, "rod_omega_z", "xdot"), {
        "hal": "bowling_3_15_8_connected_blocks.xdot = -7.00 m/s\n"
               "bowling_3_15_8_connected_blocks.rod_omega_z = 66.97 rad/s\n"})
    plan = plan_assignment(hw)

    def refuse(problem, givens):
        raise SolveError("the rod would have to stretch")

    report = grade_plan(plan, read_submissions(tmp_path / "subs", keys=plan.keys),
                        resolve=refuse)
    hal = answers_of(report, "hal")
    assert hal["rod_omega_z"].verdict == "incorrect"
    assert hal["rod_omega_z"].feedback.endswith(
        "Error carried forward could not be applied: with your x' the problem cannot be "
        "solved (the rod would have to stretch).")


def test_ecf_swaps_out_a_same_order_given_only_when_the_plain_override_conflicts(
        tmp_path, blocks_text):
    hw = ecf_class(tmp_path, with_dependency(blocks_text, "rod_omega_z", "xdot"), {
        "hal": "bowling_3_15_8_connected_blocks.xdot = -7.00 m/s\n"
               "bowling_3_15_8_connected_blocks.rod_omega_z = 66.97 rad/s\n"})
    plan = plan_assignment(hw)
    calls = []

    def resolve(problem, givens):
        calls.append(dict(givens))
        if "y'" not in givens:
            raise InconsistentError("x' and y' disagree")
        from mechgrade.solve import solve
        return solve(problem, givens=givens)

    grade_plan(plan, read_submissions(tmp_path / "subs", keys=plan.keys), resolve=resolve)
    assert calls == [{"x'": -7.0}, {"x'": -7.0, "y'": None}]


def test_ecf_is_off_when_the_assignment_says_so(tmp_path, blocks_text):
    hw = ecf_class(tmp_path, with_dependency(blocks_text, "rod_omega_z", "xdot"), {
        "hal": "bowling_3_15_8_connected_blocks.xdot = -7.00 m/s\n"
               "bowling_3_15_8_connected_blocks.rod_omega_z = 66.97 rad/s\n"})
    hw = replace(hw, policy=replace(hw.policy, ecf=replace(hw.policy.ecf, enabled=False)))
    hal = answers_of(grade_submissions(hw, tmp_path / "subs"), "hal")
    assert (hal["rod_omega_z"].verdict, hal["rod_omega_z"].feedback) == (
        "incorrect", "Not within 1% of the expected value.")


def test_given_key_of_plain_quantities(blocks_text):
    problem = load_problem_text(blocks_text, "blocks.yaml")
    assert given_key_of(problem.objective("xdot")) == "x'"
    assert given_key_of(problem.objective("rod_omega_z")) is None
    assert given_key_of(problem.objective("xdot_symbolic")) is None


# ---------------------------------------------------------------------------- the example


def test_example_class_end_to_end():
    """The README's command on the shipped example (real spec loader and solver)."""
    hw = load_assignment(EXAMPLE / "assignment.yaml")
    roster = read_roster(EXAMPLE / "roster.csv")
    report = grade_submissions(hw, EXAMPLE / "submissions", roster)
    statuses = {s.id: (s.status, s.score) for s in report.students}
    assert list(statuses) == ["ada_lovelace", "bob_roe", "carla_diaz", "dan_wu", "eve_mallory",
                              "frank_empty", "gina_cp1252", "hal_two_files", "ivy_binary",
                              "jules_noshow"]
    assert statuses["ada_lovelace"] == ("graded", 19.0)
    assert statuses["frank_empty"] == ("missing", 0.0)
    assert statuses["ivy_binary"] == ("unreadable", 0.0)
    assert statuses["jules_noshow"] == ("missing", 0.0)
    assert statuses["eve_mallory"] == ("graded", 0.0)
    bob = answers_of(report, "bob_roe")
    assert (bob["xdot"].diagnosis, bob["acc_N"].diagnosis) == ("sign error", "swapped components")
    dan = answers_of(report, "dan_wu")
    assert (dan["a_P_N"].verdict, dan["a_P_N"].points, dan["a_P_N"].diagnosis) == (
        "partial", 0.9, "The Coriolis term 2 omega x v_rel is missing.")
    carla = answers_of(report, "carla_diaz")
    assert carla["rod_omega_z"].diagnosis == "degrees used as radians"
    assert carla["P_ZA_frameA"].diagnosis == "unit slip (cm vs m)"
    gina = {s.id: s for s in report.students}["gina_cp1252"]
    assert gina.messages[0].startswith("'gina_cp1252.txt' is not UTF-8")
    assert answers_of(report, "gina_cp1252")["xdot"].verdict == "correct"
    eve = answers_of(report, "eve_mallory")
    assert eve["acc_mag"].verdict == "unreadable"
    assert report == grade_submissions(hw, EXAMPLE / "submissions", roster)


def test_the_report_is_the_same_for_any_number_of_jobs(tmp_path, blocks_text):
    """Solving, reading and judging spread over processes change nothing, ECF included."""
    hw = load_assignment(EXAMPLE / "assignment.yaml")
    roster = read_roster(EXAMPLE / "roster.csv")
    assert (grade_submissions(hw, EXAMPLE / "submissions", roster, jobs=3)
            == grade_submissions(hw, EXAMPLE / "submissions", roster, jobs=1))
    ecf = ecf_class(tmp_path, with_dependency(blocks_text, "rod_omega_z", "xdot"), {
        "hal": "bowling_3_15_8_connected_blocks.xdot = -7.00 m/s\n"
               "bowling_3_15_8_connected_blocks.rod_omega_z = 66.97 rad/s\n"})
    parallel = grade_submissions(ecf, tmp_path / "subs", jobs=2)
    assert parallel == grade_submissions(ecf, tmp_path / "subs", jobs=1)
    assert answers_of(parallel, "hal")["rod_omega_z"].verdict == "correct"


def test_carried_forward_re_solves_are_solved_ahead_over_the_jobs(tmp_path, blocks_text,
                                                                   monkeypatch):
    ecf = ecf_class(tmp_path, with_dependency(blocks_text, "rod_omega_z", "xdot"), {
        sid: f"bowling_3_15_8_connected_blocks.xdot = {xdot} m/s\n"
             f"bowling_3_15_8_connected_blocks.rod_omega_z = {omega} rad/s\n"
        for sid, xdot, omega in (("hal", "-7.00", "66.97"), ("ida", "-7.00", "60"),
                                 ("jon", "-6.50", "62.19"), ("kim", "-7.66598", "73.3429"))})
    alone = grade_submissions(ecf, tmp_path / "subs", jobs=1)
    asked, judged_alone = [], []
    real = CarriedForward._attempt
    monkeypatch.setattr(CarriedForward, "_attempt",
                        lambda self, *args: asked.append(args) or real(self, *args))
    real_assess = SandboxPool.assess
    monkeypatch.setattr(SandboxPool, "assess", lambda self, *args:
                        judged_alone.append(args) or real_assess(self, *args))
    assert grade_submissions(ecf, tmp_path / "subs", jobs=2) == alone
    assert asked == []  # every re-solve was made ahead, in the forked workers
    assert judged_alone == []  # and the answers judged again against them in a batch
    assert answers_of(alone, "hal")["rod_omega_z"].verdict == "correct"
    assert answers_of(alone, "jon")["rod_omega_z"].verdict == "correct"


_SOLVED: list = []  # (log file, real solve, pid of the test) while a test notes solves


def _noted_solve(problem, **kwargs):
    import os

    log, real, here = _SOLVED
    with open(log, "a", encoding="utf-8") as handle:
        handle.write(f"{problem.id} {os.getpid() == here}\n")
    return real(problem, **kwargs)


def test_a_problem_carried_forward_re_solves_is_solved_here_the_others_in_forked_processes(
        tmp_path, blocks_text, monkeypatch):
    import os

    import mechgrade.solve

    write(tmp_path / "blocks.yaml", with_dependency(blocks_text, "rod_omega_z", "xdot"))
    write(tmp_path / "hw.yaml", f"""\
        id: two
        title: Three problems
        problems:
          - path: blocks.yaml
            objectives: [xdot, rod_omega_z]
          - path: {shipped_dir("problems") / "bowling_3_15_2_cannonball.yaml"}
            objectives: [speed]
          - path: {shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml"}
            objectives: [acc_mag]
        """)
    hw = load_assignment(tmp_path / "hw.yaml")
    alone = run_module.plan_assignment(hw, jobs=1)
    _SOLVED[:] = [tmp_path / "where.txt", mechgrade.solve.solve, os.getpid()]
    monkeypatch.setattr(mechgrade.solve, "solve", _noted_solve)
    try:
        assert run_module.plan_assignment(hw, jobs=2).solutions == alone.solutions
    finally:
        _SOLVED.clear()
    solved = dict(line.split() for line in
                  (tmp_path / "where.txt").read_text(encoding="utf-8").splitlines())
    assert solved == {"bowling_3_15_8_connected_blocks": "True",
                      "bowling_3_15_2_cannonball": "False", "bowling_3_15_4_pendulum": "False"}


def test_a_broken_problem_is_reported_before_a_missing_folder_with_any_jobs(class_dir):
    (class_dir / PENDULUM.name).write_text(
        PENDULUM.read_text(encoding="utf-8").replace("L: 2 ft", "L: -2 furlongz"),
        encoding="utf-8")
    hw = load_assignment(class_dir / "hw.yaml")
    errors = []
    for jobs in (1, 2):
        with pytest.raises(MechgradeError) as info:
            grade_submissions(hw, class_dir / "no_such_folder", jobs=jobs)
        errors.append(str(info.value))
    assert errors[0] == errors[1] and "furlongz" in errors[0]


def test_a_missing_folder_is_reported_with_any_jobs(class_dir):
    hw = load_assignment(class_dir / "hw.yaml")
    for jobs in (1, 2):
        with pytest.raises(SubmissionError, match="expected a folder of submissions"):
            grade_submissions(hw, class_dir / "no_such_folder", jobs=jobs)


def test_answers_are_judged_once_each_in_one_batch(class_dir, monkeypatch):
    from mechgrade.grade import sandbox

    batches = []
    original = sandbox.SandboxPool.assess_many

    def spy(self, items):
        items = list(items)
        batches.append([text for text, _, _ in items])
        return original(self, items)

    monkeypatch.setattr(sandbox.SandboxPool, "assess_many", spy)
    for name in ("dee", "eli"):  # the same answers as ann
        write(class_dir / "subs" / name / "answers.txt", (class_dir / "subs" / "ann" /
                                                          "answers.txt").read_text())
    report = grade(class_dir)
    assert len(batches) == 1 and len(batches[0]) == len(set(batches[0])) == 4
    assert {s.id: s.score for s in report.students}["dee"] == 6.0


def test_unanswered_objectives_never_reveal_their_expected_answer(tmp_path):
    from mechgrade.grade.assignment import load_assignment
    from mechgrade.grade.run import grade_submissions
    from mechgrade.resources import shipped_dir

    problem = shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml"
    (tmp_path / "p.yaml").write_bytes(problem.read_bytes())
    (tmp_path / "hw.yaml").write_text("id: hw\ntitle: HW\nproblems: [p.yaml]\n"
                                      "policy: {reveal_answers: true}\n", encoding="utf-8")
    subs = tmp_path / "subs"
    subs.mkdir()
    (subs / "ann.txt").write_text("bowling_3_15_4_pendulum.acc_mag = 98.5 ft/s^2\n",
                                  encoding="utf-8")
    (subs / "empty").mkdir()
    report = grade_submissions(load_assignment(tmp_path / "hw.yaml"), subs)
    ann, empty = report.students
    assert [a.expected is not None for a in ann.answers] == [True, False, False, False]
    assert all(a.expected is None for a in empty.answers)
