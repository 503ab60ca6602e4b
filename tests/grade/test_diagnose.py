"""Automatic and author-declared diagnoses of wrong answers."""

import math

import numpy as np
import pytest
from hypothesis import given, strategies as st

from mechgrade.grade.compare import assess

from mechgrade.grade.policy import GradingPolicy
from mechgrade.grade.diagnose import (_ALL_FACTORS, CODES, Candidates, _factor, _norm,
                                      diagnose)
from mechgrade.solve.result import GeneratedMistake, MistakeValue, ObjectiveResult
from mechgrade.tolerance import agree_at_points


def within(share: float):
    """A test of closeness: every component within ``share`` of the reference's."""
    return lambda s, t: bool(np.all(np.abs(s - t) <= share * np.abs(t)))

ACC = ObjectiveResult("acc", "scalar", "ft/s^2", 98.51)
VEC = ObjectiveResult("a_P", "vector", "ft/s^2", (-66.0, -40.0, 0.0), frame="N")
SYM = ObjectiveResult("a_sym", "symbolic", "m/s^2", expr="L*sqrt(thetad**4 + thetadd**2)",
                      symbols=("L", "thetad", "thetadd"),
                      symbol_units=("m", "rad/s", "rad/s^2"))


def label(text, result=ACC):
    return assess(text, result, GradingPolicy()).diagnosis


@pytest.mark.parametrize("value, expected", [
    (-98.51, "sign error"),
    (197.0, "factor of 2"),
    (49.25, "factor of 2"),
    (98.51 * math.pi, "factor of π"),
    (98.51 / math.pi, "factor of π"),
    (98.51 * 9.80665, "factor of g"),
    (98.51 / 32.174, "factor of g"),
    (98.51 * 180 / math.pi, "degrees used as radians"),
    (98.51 * math.pi / 180, "radians used as degrees"),
    (9851.0, "unit slip (cm vs m)"),
    (0.9851, "unit slip (cm vs m)"),
    (98510.0, "unit slip (mm vs m)"),
    (98.51 * 0.3048, "unit slip (ft vs m)"),
    (98.51 * 12, "unit slip (in vs ft)"),
    (98.51 * 60 / (2 * math.pi), "unit slip (rpm vs rad/s)"),
    (98.51 * 2 * math.pi, "unit slip (revolutions vs radians)"),
    (50.0, None),
])
def test_scalar_diagnoses(value, expected):
    assert label(f"{value!r} ft/s^2") == expected


def test_rpm_slip_when_rpm_number_given_as_rad_per_second():
    spin = ObjectiveResult("w", "scalar", "rad/s", 1.2566)
    assert label("12 rad/s", spin) == "unit slip (rpm vs rad/s)"


def test_degrees_typed_without_unit_for_radians():
    angle = ObjectiveResult("theta", "scalar", "rad", 0.5236)
    judged = assess("30", angle, GradingPolicy(missing_unit="assume"))
    assert judged.diagnosis == "degrees used as radians"


def test_unit_slip_when_the_wrong_unit_is_written():
    length = ObjectiveResult("d", "scalar", "m", 2.24)
    assert label("224 m", length) == "unit slip (cm vs m)"
    assert label("2.24 ft", length) == "unit slip (ft vs m)"


@pytest.mark.parametrize("text, expected", [
    ("66 i + 40 j ft/s^2", "sign error"),
    ("-40 i - 66 j ft/s^2", "swapped components"),
    ("-66 i + 40 j ft/s^2", "wrong direction"),
    ("40 i - 66 j ft/s^2", "wrong direction"),
    ("-132 i - 80 j ft/s^2", "factor of 2"),
    ("-33 i - 20 j ft/s^2", "factor of 2"),
    ("-70 i - 42.4 j ft/s^2", "wrong magnitude"),
    ("-20.12 i - 12.19 j ft/s^2", "unit slip (ft vs m)"),
    ("-66 i - 50 j ft/s^2", None),
])
def test_vector_diagnoses(text, expected):
    assert label(text, VEC) == expected


@pytest.mark.parametrize("text, expected", [
    ("-L*sqrt(thetad^4 + thetadd^2)", "sign error"),
    ("2 L sqrt(thetad^4 + thetadd^2)", "factor of 2"),
    ("pi L sqrt(thetad^4 + thetadd^2)", "factor of π"),
    ("9.81 L sqrt(thetad^4 + thetadd^2)", "factor of g"),
    ("L*thetad^2", None),
])
def test_expression_diagnoses(text, expected):
    assert label(text, SYM) == expected


def test_author_mistakes_come_first_with_their_credit():
    result = ObjectiveResult("acc", "scalar", "ft/s^2", 98.51, mistakes=(
        MistakeValue("You left out the tangential acceleration.", 0.4, 66.0),
        MistakeValue("Sign convention reversed.", 0.8, -98.51)))
    judged = assess("66.1 ft/s^2", result)
    assert (judged.verdict, judged.credit) == ("partial", 0.4)
    assert judged.diagnosis == "You left out the tangential acceleration."
    assert judged.feedback.endswith("You left out the tangential acceleration.")
    # the declared mistake wins over the automatic sign diagnosis
    assert assess("-98.5 ft/s^2", result).credit == 0.8


def test_author_vector_mistake():
    result = ObjectiveResult("a", "vector", "ft/s^2", (-66.0, -40.0, 0.0), frame="N",
                             mistakes=(MistakeValue("Coriolis term missing.", 0.5,
                                                    (-66.0, 0.0, 0.0)),))
    judged = assess("-66 i ft/s^2", result)
    assert (judged.diagnosis, judged.credit) == ("Coriolis term missing.", 0.5)


def test_author_mistake_with_zero_credit_is_incorrect():
    result = ObjectiveResult("acc", "scalar", "ft/s^2", 98.51,
                             mistakes=(MistakeValue("Used the wrong radius.", 0.0, 50.0),))
    judged = assess("50 ft/s^2", result)
    assert (judged.verdict, judged.diagnosis) == ("incorrect", "Used the wrong radius.")


def test_unevaluable_mistakes_are_skipped():
    result = ObjectiveResult("acc", "scalar", "ft/s^2", 98.51,
                             mistakes=(MistakeValue("Broken.", 0.5, None),
                                       MistakeValue("Vector?", 0.5, (1.0, 2.0, 3.0))))
    assert assess("-98.5 ft/s^2", result).diagnosis == "sign error"


def test_zero_reference_has_no_factor_diagnoses():
    close = lambda s, t: bool(np.all(np.abs(s - t) <= 1e-9))
    assert diagnose(np.array([1.0]), np.array([0.0]), close) is None


def test_non_finite_student_values_are_not_diagnosed():
    close = lambda s, t: True
    assert diagnose(np.array([np.nan]), np.array([1.0]), close) is None


def test_every_code_can_be_given_partial_credit():
    for code in CODES:
        assert GradingPolicy(partial_credit=((code, 0.5),)).credit_for(code) == 0.5


# ---------------------------------------------------------------------------- generated mistakes

def _with_generated(*mistakes, plausible=frozenset()):
    from mechgrade.solve.result import GeneratedMistake
    return ObjectiveResult("a_P", "vector", "ft/s^2", (-66.0, -40.0, 0.0), frame="N",
                           generated_mistakes=tuple(GeneratedMistake(c, m, v)
                                                    for c, m, v in mistakes),
                           plausible=plausible)


CORIOLIS = ("drop_coriolis", "Without the Coriolis term.", (-106.0, -40.0, 0.0))
HALF = ("coriolis_half", "Without the factor 2 of the Coriolis term.", (-86.0, -40.0, 0.0))


def test_the_nearest_generated_mistake_names_the_answer():
    judged = assess("(-105.5, -40, 0) ft/s^2", _with_generated(HALF, CORIOLIS))
    assert (judged.diagnosis, judged.feedback) == ("Coriolis term left out",
                                                   "Without the Coriolis term.")


def test_a_generated_mistake_gets_the_policy_credit_of_its_family():
    judged = assess("(-106, -40, 0) ft/s^2", _with_generated(CORIOLIS),
                    GradingPolicy(partial_credit=(("drop_coriolis", 0.5),)))
    assert (judged.verdict, judged.credit) == ("partial", 0.5)


def test_an_answer_nearer_the_reference_than_the_mistake_is_not_named_by_it():
    from mechgrade.solve.result import GeneratedMistake
    loose = within(0.1)
    mistake = [(GeneratedMistake("drop_tangential", "...", 108.0), np.array([108.0]))]
    assert diagnose(np.array([103.9]), np.array([100.0]), loose, generated=mistake) is None
    assert diagnose(np.array([104.1]), np.array([100.0]), loose,
                    generated=mistake).code == "drop_tangential"


def test_the_authors_mistake_wins_over_a_generated_one():
    from dataclasses import replace
    result = replace(_with_generated(CORIOLIS),
                     mistakes=(MistakeValue("The author's words.", 0.3, (-106.0, -40.0, 0.0)),))
    assert assess("(-106, -40, 0) ft/s^2", result).diagnosis == "The author's words."


def test_a_generated_zero_velocity_is_matched_on_the_references_scale():
    rest = ("other_point", "The contact point's velocity.", (0.0, 1e-16, 0.0))
    assert assess("(0, 0, 0) ft/s^2", _with_generated(rest)).diagnosis == \
        "another point's motion"


@pytest.mark.parametrize("value", [2.008 * 98.51, 98.51 / 6.25, 98.51 * 3.1321])
def test_a_ratio_only_near_a_factor_is_no_coincidence_to_name(value):
    # inside the 1 % tolerance of 2, 2 pi and pi, but not well inside: sqrt(g) is not pi
    assert label(f"{value!r} ft/s^2") is None


def test_a_mistaken_value_that_is_not_a_zero_is_matched_on_its_own_scale():
    # 14 is within 1 % of the reference 18.68 away from 14.17, but 1.2 % from 14.17 itself
    from mechgrade.solve.result import GeneratedMistake
    close = within(0.01)
    mistake = [(GeneratedMistake("given_deg_as_rad", "...", 14.17), np.array([14.17]))]
    assert diagnose(np.array([14.0]), np.array([18.68]), close, generated=mistake) is None
    assert diagnose(np.array([14.1]), np.array([18.68]), close,
                    generated=mistake).code == "given_deg_as_rad"


@pytest.mark.parametrize("value", [98.51 * 9.80665, 98.51 * 60 / (2 * math.pi)])
def test_a_slip_the_model_cannot_make_is_not_named(value):
    from dataclasses import replace
    no_g = replace(ACC, plausible=frozenset())
    assert assess(f"{value} ft/s^2", no_g).diagnosis is None


def test_a_flipped_rate_that_flips_the_whole_answer_is_a_sign_error_saying_which():
    flipped = ("given_sign", "Your value is what q' with the opposite sign gives.",
               (66.0, 40.0, 0.0))
    judged = assess("(66, 40, 0) ft/s^2", _with_generated(flipped),
                    GradingPolicy(partial_credit=(("sign", 0.5),)))
    assert (judged.diagnosis, judged.credit, judged.feedback) == (
        "sign error", 0.5, "Your value is what q' with the opposite sign gives.")


def test_every_generated_family_is_a_policy_code_with_a_label():
    from mechgrade.grade.diagnose import GENERATED_CODES, LABELS
    assert set(GENERATED_CODES) <= set(CODES) and set(GENERATED_CODES) == set(LABELS)


WEIGHT = ("weight_omitted", "Your value is what the balances give without the weight.",
          (-106.0, -40.0, 0.0))
PUSH = ("force_omitted", "Your value is what the balances give without the push.",
        (-106.0, -40.0, 0.0))


def test_two_families_of_one_value_are_both_named_once_each():
    judged = assess("(-106, -40, 0) ft/s^2", _with_generated(WEIGHT, PUSH))
    assert judged.diagnosis == "weight left out or an applied force left out"
    assert judged.feedback == (
        "Your value is what the balances give without the weight. It is also what the "
        "balances give without the push.")


def test_two_families_within_the_tolerance_of_each_other_fit_equally():
    near = ("force_omitted", "Without the push.", (-106.3, -40.1, 0.0))
    # the nearer first
    assert assess("(-106.1, -40, 0) ft/s^2", _with_generated(near, WEIGHT)).diagnosis == \
        "weight left out or an applied force left out"
    assert assess("(-106.3, -40.1, 0) ft/s^2", _with_generated(near, WEIGHT)).diagnosis == \
        "an applied force left out or weight left out"


def test_a_family_the_answer_matches_farther_from_the_nearest_is_not_named_too():
    # both within 1 % of the answer, but 1.9 apart: more than the tolerance of either
    far = ("force_omitted", "Without the push.", (-107.9, -40.0, 0.0))
    assert assess("(-107, -40, 0) ft/s^2", _with_generated(WEIGHT, far)).diagnosis == \
        "an applied force left out"


def test_two_families_that_fit_equally_give_the_better_of_their_credits():
    policy = GradingPolicy(partial_credit=(("weight_omitted", 0.2), ("force_omitted", 0.6)))
    judged = assess("(-106, -40, 0) ft/s^2", _with_generated(WEIGHT, PUSH), policy)
    assert (judged.verdict, judged.credit) == ("partial", 0.6)


def test_one_family_twice_is_named_once():
    again = ("weight_omitted", "The other weight left out.", (-106.0, -40.0, 0.0))
    assert assess("(-106, -40, 0) ft/s^2", _with_generated(WEIGHT, again)).diagnosis == \
        "weight left out"


def test_a_physical_family_that_is_also_a_factor_of_2_is_named_alone():
    doubled = ("drop_tangential", "Without the tangential term.", (-132.0, -80.0, 0.0))
    judged = assess("(-132, -80, 0) ft/s^2", _with_generated(doubled))
    assert judged.diagnosis == "tangential term α × r left out"
    assert label(f"{2 * 98.51} ft/s^2") == "factor of 2"  # no family: the coincidence


def test_a_given_misread_that_is_a_factor_of_2_gives_way_to_a_physical_family():
    # two masses exchanged where one is twice the other: the whole answer doubled, which a
    # family of the model explains as well
    swapped = ("given_swap", "Your value is what m1 and m2 exchanged give.", (-132.0, -80.0, 0.0))
    doubled = ("drop_tangential", "Without the tangential term.", (-132.0, -80.0, 0.0))
    for order in ((swapped, doubled), (doubled, swapped)):
        assert assess("(-132, -80, 0) ft/s^2", _with_generated(*order)).diagnosis == \
            "tangential term α × r left out"
    assert assess("(-132, -80, 0) ft/s^2", _with_generated(swapped)).diagnosis == "factor of 2"


def test_a_physical_family_that_flips_the_answer_is_named_before_a_flipped_given():
    flipped = ("given_sign", "Your value is what q' with the opposite sign gives.",
               (66.0, 40.0, 0.0))
    reversed_ = ("friction_reversed", "Friction points the other way.", (66.0, 40.0, 0.0))
    assert assess("(66, 40, 0) ft/s^2", _with_generated(flipped, reversed_)).diagnosis == \
        "friction in the wrong direction"


def test_of_families_one_but_for_round_off_the_first_is_named_first():
    origin = ("drop_transport_vel", "Without the hub's velocity.", (-106.0 + 1e-13, -40.0, 0.0))
    assert assess("(-106, -40, 0) ft/s^2", _with_generated(origin, WEIGHT)).diagnosis == \
        "frame origin's velocity left out or weight left out"


def test_a_factor_the_answer_has_exactly_wins_over_a_family_only_near_it():
    # 2 pi/Omega = 2.5 s answered 1/Omega = 0.3979 s: the frequency Omega/(2 pi) = 0.3979 *
    # 1.004 is within 1 % but not within the coincidence share; the 2 pi is exact
    from mechgrade.solve.result import GeneratedMistake
    close = within(0.01)
    exact = within(0.001)
    near = [(GeneratedMistake("period_for_frequency", "...", 0.3995), np.array([0.3995]))]
    student, reference = np.array([2.5 / (2 * math.pi)]), np.array([2.5])
    assert diagnose(student, reference, close, generated=near, exact=exact).code == "rev_rad"
    # the family that fits exactly too is named
    on = [(GeneratedMistake("period_for_frequency", "...", 0.39789), np.array([0.39789]))]
    assert diagnose(student, reference, close, generated=on,
                    exact=exact).code == "period_for_frequency"
    # a factor only four times nearer than the family is no better explanation: 1.6 for
    # 3.2062 is within the share of 2, and 0.8 % from the speed at the start 1.6125
    start = [(GeneratedMistake("value_at_start", "...", 1.6125), np.array([1.6125]))]
    loose = within(0.0025)
    assert diagnose(np.array([1.6]), np.array([3.2062]), close, generated=start,
                    exact=loose).code == "value_at_start"


def test_a_rate_in_hertz_written_as_rpm_is_a_slip_of_60_where_the_model_has_both():
    # 1207.9 rpm answered with the hertz value 20.13: per minute for per second
    result = ObjectiveResult("n", "scalar", "rpm", 1207.90,
                             plausible=frozenset({"rpm_rad", "rev_rad", "min_s"}))
    assert assess("20.13 rpm", result).diagnosis == "unit slip (per minute vs per second)"
    # the right answer in revolutions per second is right; 2.013 is no slip of 60
    assert (assess("20.13 rev/s", result).verdict, assess("20.13 rev/s", result).diagnosis) \
        == ("correct", None)
    assert assess("2.013 rpm", result).diagnosis is None
    # a model without a rate in rpm and one per second: 60 is no slip to name
    alone = ObjectiveResult("n", "scalar", "rpm", 1207.90, plausible=frozenset({"rpm_rad"}))
    assert assess("20.13 rpm", alone).diagnosis is None


def test_a_horsepower_taken_as_746_ft_lbf_per_s_where_the_model_is_in_feet_and_pounds():
    # T v = 42,000 ft lbf/s is 76.36 hp, and 56.30 "hp" divided by 746
    result = ObjectiveResult("P", "scalar", "hp", 42000 / 550,
                             plausible=frozenset({"g", "hp_746"}))
    assert assess("56.30 hp", result).diagnosis == "unit slip (1 hp taken as 746 ft·lbf/s)"
    assert assess("76.36 hp", result).diagnosis is None
    assert assess("60.00 hp", result).diagnosis is None
    si = ObjectiveResult("P", "scalar", "hp", 42000 / 550, plausible=frozenset({"g"}))
    assert assess("56.30 hp", si).diagnosis is None


@pytest.mark.parametrize("plausible", [None, frozenset(), frozenset({"g", "rpm_rad"})])
def test_factors_tested_at_once_name_what_the_test_one_by_one_names(plausible):
    reference = np.array([1.5, -2.0, 3.25, 0.5])
    test = agree_at_points(0.01, reference)
    one_by_one = lambda s, t: test(s, t)  # noqa: E731 - a plain callable: no vectorised path
    for factor in [*_ALL_FACTORS, 1.3, 0.0]:
        student = factor * reference
        assert _factor(student, reference, test, plausible) == \
            _factor(student, reference, one_by_one, plausible)
        # prepared once for the reference, as a class's answers are tried
        assert _factor(student, reference, test, plausible,
                       Candidates([], reference, test)) == \
            _factor(student, reference, one_by_one, plausible)
    assert _factor(-reference, reference, test, plausible)[0].code == "sign"
    assert _factor(1.3 * reference, reference, test, plausible) is None


def test_the_grading_docs_list_every_generated_mistake_code():
    from pathlib import Path

    from mechgrade.grade.diagnose import GENERATED_CODES

    docs = (Path(__file__).resolve().parents[2] / "docs" / "grading.md").read_text(
        encoding="utf-8")
    assert [code for code in GENERATED_CODES if f"`{code}`" not in docs] == []


@pytest.mark.parametrize("seed", range(20))
def test_candidates_kept_for_many_answers_name_what_the_list_names(seed):
    rng = np.random.default_rng(seed)
    reference = rng.normal(size=6)
    test, exact = agree_at_points(0.01, reference), agree_at_points(1e-6, reference)
    codes = ("weight_omitted", "friction_reversed", "force_omitted", "spring_omitted")
    # values away from the answer, a zero on the reference's scale, and far
    values = [reference * 1.3, reference * 0.005, rng.normal(size=6), reference * 1.3 + 1e-4]
    generated = [(GeneratedMistake(code, code, "x"), v) for code, v in zip(codes, values)]
    kept = Candidates(generated, reference, test)
    for student in (reference * 1.3, reference * 1.3005, reference * 0.0052, -reference,
                    rng.normal(size=6)):
        assert diagnose(student, reference, test, generated=kept) == \
            diagnose(student, reference, test, generated=generated) == \
            diagnose(student, reference, lambda s, t: test(s, t), generated=generated)
        # kept for another exact test: worked out again for this one
        assert diagnose(student, reference, test, generated=kept, exact=exact) == \
            diagnose(student, reference, test, generated=generated, exact=exact)


@given(st.lists(st.floats(allow_nan=True, allow_infinity=True, width=64), min_size=1,
                max_size=12))
def test_distances_are_numpys_norms_to_the_last_bit(values):
    array = np.array(values)
    with np.errstate(all="ignore"):  # overflowing squares warn alike
        assert repr(_norm(array)) == repr(float(np.linalg.norm(array)))
