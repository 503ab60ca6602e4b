"""Grade every hand-computed mistake of the held-out problems and say how mechgrade diagnosed it.

Run: python tests/data/heldout/measure.py [-v] [PROBLEM ...]   (with the mechgrade to measure importable)

The tables beside this file were computed by hand (typical.py) before mechgrade's mistake
families were read, and are frozen. Each row's ``kind`` is a name of typical.py's own vocabulary;
this file says which of mechgrade's diagnosis codes name each kind (EQUIVALENT, written after the
tables were frozen, from the codes' labels and messages). A row is

- ``named``: the diagnosis is one of the codes equivalent to its kind (a unit slip only when the
  code's units are the ones the row's mistake mixes, or a given's unit not converted; an
  applied force left out when the row's words name that load, not the weight: LOAD_LEFT_OUT);
- ``generic``: some feedback that is true of the answer but does not name the mistake (a vector
  that is right in direction or magnitude only, components swapped, or a numeric factor that the
  answer has exactly but that is not the mistake's);
- ``none``: judged wrong without a diagnosis;
- ``misleading``: a diagnosis that names another mistake (a physical family that is not the
  row's, or a numeric factor the answer does not have to its four written figures);
- ``credited``: judged correct although the mistake is outside the default tolerance.

A row marked ``inside`` (the mistake is within the tolerance) is expected to be judged correct:
it is counted apart (``inside``), and as ``misleading`` if it gets a diagnosis.
False alarms: every numeric objective's correct answer in several notations (three significant
figures, another unit of the same kind, the i/j form of vectors, five figures, e-notation, no
space before the unit) must be judged correct with no diagnosis.
"""
from __future__ import annotations

import importlib.util
import sys
from collections import Counter
from functools import lru_cache
from pathlib import Path

import numpy as np
import yaml

from mechgrade.grade.compare import assess
from mechgrade.grade.diagnose import FACTOR_CODES
from mechgrade.solve import solve
from mechgrade.spec import load_problem

HERE = Path(__file__).parent
ROOT = HERE.parents[2]
CLASSES = ("named", "generic", "none", "misleading", "credited")


def _module(path: Path, name: str):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


LIBRARY = _module(HERE.parent / "mistakes" / "measure.py", "mistakes_measure")

# which of mechgrade's codes name each kind of typical.py (an empty set: no family names it)
EQUIVALENT: dict[str, frozenset[str]] = {k: frozenset(v) for k, v in {
    "constant_acceleration": ("force_taken_constant", "mean_of_end_rates",
                              "end_speed_throughout"),
    "initial_speed_forgotten": ("initial_speed_omitted", "value_at_start"),
    "sign": ("sign", "given_sign", "direction", "acceleration_reversed",
             "omega_reversed", "spring_work_reversed",
             "force_component_reversed", "given_angle_sign"),
    "sin_cos_swap": ("given_complement", "angle_complement"),
    "deg_as_rad": ("given_deg_as_rad", "deg_as_rad", "rad_as_deg"),
    "normal_as_weight": ("normal_from_weight", "reaction_as_weight"),
    "friction_as_mu_m_g": ("normal_from_weight",),
    "friction_reversed": ("friction_reversed",),
    "tension_as_weight": ("tension_as_weight", "reaction_as_weight"),
    "reaction_as_static": ("reaction_as_weight", "tension_as_weight", "reaction_as_static",
                           "reaction_omitted"),
    "weight_for_mass": ("g", "mass_for_weight", "weight_for_mass"),
    "unit_slip": ("given_rate_unit", "given_length_unit", "given_unit", "rpm_rad", "rev_rad", "cm_m", "mm_m",
                  "ft_m", "in_ft", "min_s", "hp_746"),
    "hz_for_rad_s": ("rev_rad",),
    "period_for_frequency": ("period_for_frequency",),
    "series_parallel": ("springs_in_series",),
    "inertia_about_wrong_point": ("central_inertia_at_pivot", "parallel_axis_with_radius"),
    "inertia_wrong_shape": ("other_shape_inertia",),
    "massless_rotor": ("rotational_ke_omitted", "body_ke_omitted", "inertia_omitted"),
    "coriolis_dropped": ("drop_coriolis",),
    "coriolis_halved": ("coriolis_half",),
    "centripetal_dropped": ("drop_centripetal", "acc_t_for_acc"),
    "tangential_dropped": ("drop_tangential", "acc_n_for_acc"),
    "curvature_without_slope": ("rho_without_slope",),
    "velocity_component_wrong": ("component_for_speed", "speed_for_component",
                                 "drop_relative_vel", "drop_transport_vel"),
    "kinematic_factor": ("other_point", "drop_omega_r", "drop_transport_vel",
                         "drop_transport_acc", "relative_omega", "surface_taken_fixed",
                         "position_term", "strands_miscounted", "load_at_other_point",
                         "contact_taken_smooth", "gyration_for_radius",
                         "moment_arm_omitted", "driver_speed",
                         "rate_relation_inverted",
                         "initial_displacement_omitted", "angmom_along_axis",
                         "spring_force_as_resultant", "part_moving_with_centre",
                         "striker_stops"),
    "angular_rate_equal": ("driver_rate",),
    "acceleration_zero_constant_speed": ("zero_for_constant_rate",),
    "spring_energy_total_length": ("spring_free_length_omitted",),
    "spring_energy_difference": ("spring_energy_from_change",),
    "spring_term_dropped": ("spring_omitted",),
    "gravity_dropped": ("weight_omitted",),
    "ke_conserved": ("restitution_ignored", "energy_kept_in_coupling"),
    "head_on": ("impact_taken_head_on",),
    "restitution_wrong_component": ("restitution_component",),
    "restitution_ignored": ("restitution_ignored",),
    "momentum_with_pin": ("pin_impulse_omitted",),
    "efficiency_inverted": ("efficiency_inverted",),
    "acceleration_term_dropped": ("reaction_as_weight", "tension_as_weight",
                                  "reaction_as_static", "given_acceleration_zero"),
    "speed_conserved": ("value_at_start", "transverse_speed_kept"),
    "half_factor": ("factor_2", "spring_energy_half_omitted"),
    "rolling_assumed": ("rolling_assumed",),
    "damping_ignored": ("damping_omitted",),
    "translation_ke_dropped": ("translational_ke_omitted",),
    "wrong_root": (),
    "magnitudes_added": ("mag_as_sum",),
}.items()}

# a unit-slip code names the row's slip when the row's words mention one of its units
UNIT_WORDS = {"rpm_rad": ("rpm",), "rev_rad": ("rev", "hertz", "Hz"), "cm_m": ("cm",),
              "mm_m": ("mm",), "ft_m": ("ft",), "in_ft": ("lb/in", " in "),
              "min_s": ("rpm", "Hz", "hertz", "minute"), "hp_746": ("hp",)}
# typical.py's vocabulary has no kind for an applied force (a drag, a push) left out: its rows
# write it as gravity_dropped. An applied force left out names such a row when the row's words
# name the load it leaves out and it is not the weight ("resistance left out").
LOAD_LEFT_OUT = {"gravity_dropped": ("force_omitted",)}
GRAVITY_WORDS = ("gravity", "weight", "g sin", "m g")


def load_left_out(code: str, row: dict) -> bool:
    """Whether ``code`` names the row as a load other than the weight left out
    (:data:`LOAD_LEFT_OUT`)."""
    return code in LOAD_LEFT_OUT.get(row["kind"], ()) and "left out" in row["mistake"] \
        and not any(w in row["mistake"] for w in GRAVITY_WORDS)


# whole-answer diagnoses that are true of an answer without naming its mistake
SHAPE_CODES = frozenset({"direction", "magnitude", "swapped", "dimension", "shape",
                         "missing_unit", "sig_figs", "frame"})
FACTORS = {"sign": (-1.0,), "factor_2": (2.0, 0.5), "deg_as_rad": (180 / np.pi,),
           "rad_as_deg": (np.pi / 180,), "pi": (np.pi, 1 / np.pi),
           "rev_rad": (2 * np.pi, 1 / (2 * np.pi)), "rpm_rad": (60 / (2 * np.pi), 2 * np.pi / 60),
           "g": (9.80665, 32.174, 1 / 9.80665, 1 / 32.174), "cm_m": (100.0, 0.01),
           "mm_m": (1000.0, 0.001), "ft_m": (1 / 0.3048, 0.3048), "in_ft": (12.0, 1 / 12),
           "min_s": (60.0, 1 / 60), "hp_746": (550 / 746, 746 / 550)}


@lru_cache(maxsize=None)
def solution(problem: str):
    return solve(load_problem(ROOT / "problems" / f"{problem}.yaml"))


def tables() -> dict[str, list[dict]]:
    """Problem id -> its frozen rows."""
    return {path.stem: yaml.safe_load(path.read_text(encoding="utf-8"))
            for path in sorted(HERE.glob("*.yaml"))}


def _exact_factor(code: str, answer: str, result) -> bool:
    """Whether the answer (written in the objective's unit, to four figures) is the code's
    factor times the reference, to the rounding of its fourth figure."""
    value = _read(answer)
    reference = np.atleast_1d(np.asarray(result.value, float))
    if value.shape != reference.shape:
        return False
    return any(np.allclose(value, f * reference, rtol=5e-4, atol=1e-12)
               for f in FACTORS.get(code, ()))


def _read(answer: str) -> np.ndarray:
    text = answer.strip()
    if text.startswith("("):
        return np.array([float(x) for x in text[1:text.index(")")].split(",")])
    return np.array([float(text.split()[0])])


def _codes(label: str, result) -> list[str]:
    """The diagnosis codes behind an assessment's label (a vector's labels are joined by ';',
    two families that fit equally by ' or ')."""
    return [code for part in label.split(";") for code in LIBRARY.codes_of(part.strip(), result)]


def classify(row: dict, result) -> tuple[str, object]:
    """The class of one row (module docstring), and mechgrade's assessment of it."""
    judged = assess(row["answer"], result)
    if judged.verdict == "correct":
        return ("inside" if row.get("inside") else "credited"), judged
    if judged.diagnosis is None:
        return "none", judged
    if row.get("inside"):
        return "misleading", judged
    codes = _codes(judged.diagnosis, result)
    named = EQUIVALENT[row["kind"]]
    for code in codes:
        if code == "direction" and not _exact_factor("sign", row["answer"], result):
            continue  # "wrong direction" names a sign only when the whole vector is reversed
        if code in named:
            words = UNIT_WORDS.get(code)
            if row["kind"] == "unit_slip" and words is not None \
                    and not any(w in row["mistake"] for w in words):
                continue
            return "named", judged
        if load_left_out(code, row):
            return "named", judged
    if all(c in SHAPE_CODES or (c in FACTOR_CODES and _exact_factor(c, row["answer"], result))
           for c in codes):
        return "generic", judged
    return "misleading", judged


def topic(problem_id: str) -> str:
    """The problem's first tag: its topic in the per-topic figures."""
    tags = load_problem(ROOT / "problems" / f"{problem_id}.yaml").tags
    return tags[0] if tags else "untagged"


def notations(result):
    """Correct answers as the library's tests write them, and three more ways: five figures,
    e-notation, and no space before the unit."""
    yield from LIBRARY.notations(result)
    unit = result.unit
    u = "" if unit in ("", "1") else unit
    if result.kind == "vector":
        yield "(" + ", ".join(f"{v:.5g}" for v in result.value) + f") {u}"
        return
    value = result.value
    yield f"{value:.5g} {u}".strip()
    yield f"{value:.3e} {u}".strip()
    yield f"{value:.4g}{u}"


def false_alarms(problem_id: str) -> list[tuple[str, str, object]]:
    """``(objective, text, assessment)`` for each correct notation not judged correct and quiet."""
    out = []
    for result in solution(problem_id).results:
        if result.kind == "symbolic" or result.value is None:
            continue
        for text in notations(result):
            judged = assess(text, result)
            if (judged.verdict, judged.diagnosis) != ("correct", None):
                out.append((result.id, text, judged))
    return out


def measure(verbose: bool = False, out=sys.stdout, problems=None) -> dict[str, Counter]:
    """Classify every row (of ``problems`` only, when given), print the figures per problem,
    per topic and overall; the counts by problem id (and ``"*"`` for all), with
    ``false_alarms`` and ``notations`` keys."""
    counts: dict[str, Counter] = {}
    by_topic: dict[str, Counter] = {}
    missing: Counter = Counter()
    for problem, rows in tables().items():
        if problems is not None and problem not in problems:
            continue
        counted = counts.setdefault(problem, Counter())
        for row in rows:
            kind, judged = classify(row, solution(problem).result(row["objective"]))
            counted[kind] += 1
            if kind != "named" and kind != "inside":
                missing[row["kind"]] += 1
            if verbose or kind not in ("named", "inside"):
                print(f"{kind:10} {problem}.{row['objective']}: {row['mistake']} [{row['kind']}]"
                      f" -> {judged.diagnosis!r}", file=out)
        alarms = false_alarms(problem)
        for objective, text, judged in alarms:
            print(f"ALARM      {problem}.{objective}: {text!r} -> {judged.verdict} "
                  f"{judged.diagnosis!r}", file=out)
        counted["false_alarms"] += len(alarms)
        counted["notations"] += sum(len(list(notations(r))) for r in solution(problem).results
                                    if r.kind != "symbolic" and r.value is not None)
        by_topic.setdefault(topic(problem), Counter()).update(counted)
    total = sum(counts.values(), Counter())
    print("\nper problem:", file=out)
    for problem, counted in counts.items():
        print(f"  {problem:36} {rate(counted)}", file=out)
    print("per topic (first tag):", file=out)
    for name, counted in sorted(by_topic.items()):
        print(f"  {name:36} {rate(counted)}", file=out)
    print(f"all {len(counts)} problems: {rate(total)}", file=out)
    absent = Counter({k: n for k, n in missing.items() if not EQUIVALENT[k]})
    unfired = Counter({k: n for k, n in missing.items() if EQUIVALENT[k]})
    print("not named, no family for the kind: "
          + ", ".join(f"{k} {n}" for k, n in absent.most_common()), file=out)
    print("not named, a family exists but did not name it here: "
          + ", ".join(f"{k} {n}" for k, n in unfired.most_common()), file=out)
    counts["*"] = total
    return counts


def rate(counted: Counter) -> str:
    graded = sum(counted[k] for k in CLASSES)
    shares = ", ".join(f"{k} {counted[k]} ({100 * counted[k] / graded:.0f} %)" if graded else
                       f"{k} 0" for k in CLASSES)
    return (f"{shares} of {graded}; inside {counted['inside']}; false alarms "
            f"{counted['false_alarms']} of {counted['notations']} notations")


if __name__ == "__main__":
    named = [a for a in sys.argv[1:] if not a.startswith("-")]
    unknown = sorted(set(named) - set(tables()))
    if unknown:
        sys.exit(f"measure.py: no held-out table for {', '.join(unknown)}")
    measure("-v" in sys.argv, problems=set(named) or None)
