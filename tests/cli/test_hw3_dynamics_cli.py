"""``mechgrade grade`` on examples/hw3_dynamics, as an instructor runs it: a dynamics homework
(Atwood machine, block on a rough incline, a pendulum released from rest, a spring chain) with
right answers in other units and notations, typical dynamics mistakes, error carried forward
through a work-energy balance, an empty and a malformed submission.

Every student's values are worked out by hand in their answer files (comments) and in the
problem's comments; nothing here was copied from the solver.
"""

from __future__ import annotations

import csv
import json

import pytest
from click.testing import CliRunner

from mechgrade.cli import main
from mechgrade.resources import shipped_dir

HW3 = shipped_dir("examples") / "hw3_dynamics"


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def grade(out, *options):
    return run("grade", HW3 / "assignment.yaml", HW3 / "submissions", "--roster",
               HW3 / "roster.csv", "--out", out, *options)


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    # in this process: forked workers would each derive the four problems again (no disk
    # cache in the tests); the class graded over two workers is checked against it below
    out = tmp_path_factory.mktemp("hw3") / "out"
    result = grade(out, "--jobs", "1")
    return result, out, json.loads((out / "results.json").read_text(encoding="utf-8"))


@pytest.mark.slow  # the class graded again over two workers, each deriving it cold
def test_grading_hw3_over_two_workers_writes_the_same_files(graded, tmp_path):
    result, out, _ = graded
    parallel = grade(tmp_path / "out", "--jobs", "2")
    assert parallel.exit_code == 0, parallel.output
    assert parallel.stdout == result.stdout.replace(out.as_posix(), (tmp_path / "out").as_posix())
    written = sorted(p.relative_to(out) for p in out.rglob("*") if p.is_file())
    assert sorted(p.relative_to(tmp_path / "out") for p in (tmp_path / "out").rglob("*")
                  if p.is_file()) == written
    for name in written:
        if name.name != "manifest.json":  # it records the command and its options
            assert (tmp_path / "out" / name).read_bytes() == (out / name).read_bytes(), name


def answers(results, sid):
    student = next(s for s in results["students"] if s["id"] == sid)
    return {f"{a['problem']}.{a['objective']}": a for a in student["answers"]}


def test_grading_hw3_exits_0_with_the_summary(graded):
    result, out, _ = graded
    assert result.exit_code == 0, result.output
    assert result.stdout == (
        f"Graded 8 students (1 unreadable answer, 1 unreadable submission, 1 missing "
        f"submission, 1 skipped entry); wrote {out.as_posix()}/\n"
        f"Skipped (not read as anyone's answers):\n"
        f"  ivan_empty/.keep: hidden (its name starts with '.')\n")


def test_every_student_has_the_status_and_score_worked_out_by_hand(graded):
    _, _, results = graded
    assert [(s["id"], s["status"], s["score"], s["max_score"]) for s in results["students"]] == [
        ("ana_alvarez", "graded", 34.0, 34.0),    # all right: g0, lbf, cm/s^2, kN, cw, deg/s^2, mJ
        ("ben_okafor", "graded", 31.0, 34.0),     # friction along N's unit vectors (-3)
        ("carla_diaz", "graded", 6.5, 34.0),
        ("dan_wu", "graded", 9.0, 34.0),        # friction reversed: no sign credit
        ("erin_park", "graded", 32.0, 34.0),      # only (a) lost: (c), (d) by ECF
        ("femi_adeyemi", "graded", 14.0, 34.0),
        ("gus_schmidt", "graded", 29.5, 34.0),    # three sign errors at half credit
        ("hana_kim", "graded", 34.0, 34.0),       # kN, kJ, kW, rev/s, N.x + N.y
        ("ivan_empty", "missing", 0.0, 34.0),
        ("jo_broken", "unreadable", 0.0, 34.0),
    ]


# (student, objective): (verdict, points, diagnosis) of every answer that is not plainly right.
# None where no diagnosis is known: a1 = 0 from a tension taken equal to a weight, Erin's omega.
# Two families that give one value are both named ("X or Y").
CENTRAL_AT_PIVOT = "inertia about the mass centre used at the pivot"
NOT_PLAINLY_RIGHT = {
    ("ben_okafor", "block_sliding_down_incline.friction"): ("incorrect", 0.0, "wrong frame"),
    ("carla_diaz", "atwood_machine.a1"): ("incorrect", 0.0, None),
    ("carla_diaz", "atwood_machine.tension"): (
        "incorrect", 0.0, "tension taken equal to a weight"),  # a tension is a reaction: one reading
    ("carla_diaz", "atwood_machine.tension_symbolic"): ("partial", 0.75,
                                                     "mass used for the weight"),
    ("carla_diaz", "block_sliding_down_incline.accel"): ("incorrect", 0.0, None),
    ("carla_diaz", "block_sliding_down_incline.normal"): ("partial", 0.5,
                                                       "mass used for the weight"),
    ("carla_diaz", "block_sliding_down_incline.friction"): ("partial", 0.75,
                                                         "mass used for the weight"),
    ("carla_diaz", "block_sliding_down_incline.accel_symbolic"): (
        "partial", 0.5, "mass used for the weight or weight used for the mass"),
    ("carla_diaz", "pendulum_release.eom"): ("incorrect", 0.0, "number typed for g"),
    ("dan_wu", "block_sliding_down_incline.accel"): (
        "incorrect", 0.0, "friction in the wrong direction or given rate's sign flipped"),
    ("dan_wu", "block_sliding_down_incline.friction"): ("incorrect", 0.0,
                                                      "friction in the wrong direction"),
    ("dan_wu", "block_sliding_down_incline.accel_symbolic"): ("incorrect", 0.0,
                                                            "friction in the wrong direction"),
    ("dan_wu", "pendulum_release.omega"): ("incorrect", 0.0, CENTRAL_AT_PIVOT),
    ("dan_wu", "pendulum_release.alpha"): ("incorrect", 0.0, CENTRAL_AT_PIVOT),
    ("dan_wu", "pendulum_release.pin_force"): ("incorrect", 0.0, CENTRAL_AT_PIVOT),
    ("dan_wu", "pendulum_release.eom"): ("incorrect", 0.0, CENTRAL_AT_PIVOT),
    ("dan_wu", "two_mass_spring_chain.spring1_energy"): ("incorrect", 0.0, "factor of 2"),
    ("dan_wu", "two_mass_spring_chain.ke2"): ("incorrect", 0.0, "factor of 2"),
    ("dan_wu", "two_mass_spring_chain.damper_power"): ("partial", 1.0, "sign error"),
    ("erin_park", "pendulum_release.omega"): ("incorrect", 0.0, None),
    ("erin_park", "pendulum_release.pin_force"): ("correct", 3.0, "error carried forward"),
    ("erin_park", "pendulum_release.kinetic_energy"): ("correct", 2.0, "error carried forward"),
    ("femi_adeyemi", "atwood_machine.a1"): ("incorrect", 0.0, "wrong dimension"),
    ("femi_adeyemi", "atwood_machine.tension"): ("partial", 1.0, "missing unit"),
    ("femi_adeyemi", "atwood_machine.tension_symbolic"): ("incorrect", 0.0, "wrong dimension"),
    ("femi_adeyemi", "block_sliding_down_incline.normal"): ("incorrect", 0.0,
                                                          "reaction taken equal to the weight"),
    ("femi_adeyemi", "block_sliding_down_incline.friction"): ("incorrect", 0.0,
                                                              "normal force taken as the weight"),
    ("femi_adeyemi", "block_sliding_down_incline.accel_symbolic"): ("incorrect", 0.0,
                                                                  "normal force taken as the weight"),
    ("femi_adeyemi", "pendulum_release.pin_force"): ("incorrect", 0.0, "weight left out"),
    ("femi_adeyemi", "two_mass_spring_chain.ke2"): ("incorrect", 0.0, "wrong dimension"),
    ("gus_schmidt", "atwood_machine.a1"): ("partial", 1.0, "sign error"),
    ("gus_schmidt", "block_sliding_down_incline.friction"): ("partial", 1.5, "missing unit"),
    ("gus_schmidt", "pendulum_release.alpha"): ("partial", 1.0, "sign error"),
    ("gus_schmidt", "two_mass_spring_chain.damper_power"): ("partial", 1.0, "sign error"),
    ("femi_adeyemi", "pendulum_release.kinetic_energy"): ("unreadable", 0.0, None),
}


def test_each_mistake_gets_its_verdict_points_and_diagnosis(graded):
    _, _, results = graded
    found = {}
    for student in results["students"]:
        if student["status"] != "graded":
            continue
        for answer in student["answers"]:
            key = (student["id"], f"{answer['problem']}.{answer['objective']}")
            judged = (answer["verdict"], answer["points"], answer["diagnosis"])
            if answer["verdict"] != "missing" and judged != ("correct", answer["max_points"],
                                                            None):
                found[key] = judged
    assert found == NOT_PLAINLY_RIGHT


def test_dynamics_feedback_names_the_mistaken_load_and_the_dimension(graded):
    _, _, results = graded
    carla, femi = answers(results, "carla_diaz"), answers(results, "femi_adeyemi")
    assert carla["block_sliding_down_incline.normal"]["feedback"] == (
        "Your value is what the balances give with the mass of block written for its weight; "
        "the weight is m g = 39.24 N: multiply the mass by g.")
    assert carla["atwood_machine.tension_symbolic"]["feedback"] == (
        "Your value is what the balances give with the mass of block1, block2 written for "
        "their weight; the weight is m g: multiply the mass by g.")
    assert femi["two_mass_spring_chain.ke2"]["feedback"] == (
        "You gave a power ([mass]·[length]²/[time]³); an energy or moment "
        "([mass]·[length]²/[time]²) was asked.")
    assert femi["pendulum_release.pin_force"]["feedback"] == (
        "Your value leaves the weight of rod (m g = 19.62 N) out of the force balance that "
        "gives R_O: R_O + m g = m a_G.")


def test_ecf_credits_the_pin_force_and_energy_that_follow_from_a_wrong_rate(graded):
    _, _, results = graded
    erin, dan = answers(results, "erin_park"), answers(results, "dan_wu")
    for key in ("pendulum_release.pin_force", "pendulum_release.kinetic_energy"):
        assert erin[key]["feedback"] == (  # one sentence, nothing about the reference
            "Error carried forward: this answer follows correctly from your answer to omega "
            "(used in place of the energy balance) and earns 100% of the points.")
    # Dan's pin force uses his wrong alpha as well: it follows from neither answer
    assert dan["pendulum_release.pin_force"]["feedback"].endswith(
        "Also checked with your own answer to omega (error carried forward): it does not "
        "follow from it either.")


def test_a_student_credited_by_ecf_reads_why_on_the_feedback_page(graded):
    _, out, _ = graded
    for page in sorted((out / "feedback").glob("erin_park*")):
        text = page.read_text(encoding="utf-8")
        # the objective's symbol as a textbook writes it (issue 20), in either page
        assert "Error carried forward: this answer follows correctly from your answer to ω" \
            in text, page.name


def test_right_answers_in_other_units_notations_and_labels_are_read(graded):
    _, _, results = graded
    read = {(sid, key): a["read_back"] for sid in ("ana_alvarez", "gus_schmidt", "hana_kim")
            for key, a in answers(results, sid).items()}
    assert read[("ana_alvarez", "pendulum_release.omega")] == "-4.33 rad/s"
    assert read[("ana_alvarez", "block_sliding_down_incline.friction")] == \
        "(-8.50, 0, 0) N in frame A"
    assert read[("gus_schmidt", "pendulum_release.eom")] == "-3*g*sin(theta)/(2*L)"
    # sliding down, as stated: friction's sign(x') is +1 (Erin wrote it, Ana and Gus did not)
    assert read[("gus_schmidt", "block_sliding_down_incline.accel_symbolic")] == \
        "g*(sin(beta) - mu_k*cos(beta))"
    assert read[("hana_kim", "pendulum_release.pin_force")] == "(-21.74, 30.81, 0) N in frame N"
    assert read[("hana_kim", "pendulum_release.omega")] == "-0.690 revolution/s"
    assert answers(results, "femi_adeyemi")["pendulum_release.kinetic_energy"]["feedback"] == (
        "Could not read the answer: expected a unit such as 'J', found 'Nm' in 'Nm' (not a "
        "unit here: write N*m for newton metres).")


def test_report_and_canvas_export_of_hw3(graded, tmp_path):
    _, out, _ = graded
    report = run("report", out / "results.json", "--out", tmp_path / "class_report.html")
    assert report.exit_code == 0, report.output
    page = (tmp_path / "class_report.html").read_text(encoding="utf-8")
    assert ("<td>(c) The force of the pin on the rod at theta = 40 deg, in the inertial unit "
            'vectors.<code class="key">pendulum_release.pin_force</code></td>') in page
    export = run("export", out / "results.json", "--format", "canvas", "--roster",
                 HW3 / "roster.csv", "--out", tmp_path / "canvas.csv")
    assert export.exit_code == 0, export.output
    rows = list(csv.reader((tmp_path / "canvas.csv").open(encoding="utf-8")))
    assert rows[1][-1] == "34"
    assert [(row[3], row[-1]) for row in rows[2:]] == [
        ("ana_alvarez", "34"), ("ben_okafor", "31"), ("carla_diaz", "6.5"), ("dan_wu", "9"),
        ("erin_park", "32"), ("femi_adeyemi", "14"), ("gus_schmidt", "29.5"),
        ("hana_kim", "34"), ("ivan_empty", "0"), ("jo_broken", "0")]


@pytest.mark.slow
@pytest.mark.parametrize("page", ["feedback/dan_wu.html", "feedback/erin_park.html",
                                  "feedback/jo_broken.html"])
def test_dynamics_feedback_pages_pass_axe_core_wcag_2_a_and_aa(graded, axe, page):
    _, out, _ = graded
    assert axe(out / page) == []


@pytest.mark.slow
def test_the_class_report_of_hw3_passes_axe_core_and_fits_a_phone(graded, tmp_path, axe, phone):
    _, out, _ = graded
    assert run("report", out / "results.json", "--out", tmp_path / "report.html").exit_code == 0
    assert axe(tmp_path / "report.html") == []
    laid_out = phone(tmp_path / "report.html")
    assert laid_out["past"] == [] and laid_out["page"] <= 375, laid_out


def test_a_student_credited_by_ecf_reads_one_sentence_under_its_verdict(graded):
    _, out, _ = graded
    page = (out / "feedback" / "erin_park.md").read_text(encoding="utf-8")
    card = page[page.index("## (d) The rod's kinetic energy"):]
    card = card[:card.index("\n## ")]
    assert card == (
        "## (d) The rod's kinetic energy at θ = 40 deg. — 2 / 2\n\n"
        "Answer key `pendulum_release.kinetic_energy`\n\n"
        "Error carried forward: this answer follows correctly from your answer to ω (used "
        "in place of the energy balance) and earns 100% of the points.\n\n"
        "- Verdict: **Correct (error carried forward)**\n"
        "- Your answer: 18.0 J\n"
        "- Read as: 18.0 J\n"
        "- Expected: 9.018 J\n")


def test_an_unreadable_file_gets_one_card_listing_the_questions_and_their_keys(graded):
    _, out, _ = graded
    page = (out / "feedback" / "jo_broken.html").read_text(encoding="utf-8")
    assert page.count('<section class="objective') == 1
    assert ("<p class=\"note\">Your answers could not be read (see “About your submission”), so "
            "none of the 15 questions was graded.</p>") in page
    assert ("<tr><td>The string tension.</td><td><code>atwood_machine.tension</code></td>"
            '<td class="pts">0 / 2</td></tr>') in page
