"""Property: whatever text, bytes or folder name a student hands in, the full grading pipeline
(read, grade, write every output) finishes, and the student is in every output."""

from __future__ import annotations

import csv
import io
import json
import os
import shutil
import tempfile

import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from mechgrade.export.cells import safe_cell
from mechgrade.files import clean_text
from mechgrade.grade.assignment import load_assignment
from mechgrade.grade.run import grade_plan, plan_assignment
from mechgrade.grade.submissions import read_submissions
from mechgrade.report.output import feedback_names, write_outputs
from mechgrade.resources import shipped_dir

KEY = "bowling_3_15_4_pendulum.acc_mag"


@pytest.fixture(scope="module")
def plan(tmp_path_factory):
    top = tmp_path_factory.mktemp("plan")
    problem = shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml"
    (top / "p.yaml").write_bytes(problem.read_bytes())
    (top / "hw.yaml").write_text("id: hw\ntitle: HW\nproblems: [p.yaml]\n", encoding="utf-8")
    return plan_assignment(load_assignment(top / "hw.yaml"))


# A folder name is any bytes but '/' and NUL, and neither '.' nor '..'.
names = st.binary(min_size=1, max_size=60).map(
    lambda b: b.replace(b"/", b"_").replace(b"\0", b"_")).filter(lambda b: b not in (b".", b".."))
texts = st.text(max_size=300)
contents = st.one_of(
    st.binary(max_size=400),
    texts.map(lambda t: f"{KEY} = {t}\n".encode("utf-8", "surrogatepass")),
    texts.map(lambda t: json.dumps({KEY: t}).encode()),
    texts.map(lambda t: f"{KEY}: {t}\n".encode("utf-8", "surrogatepass")),
)
files = st.sampled_from([b"answers.txt", b"answers.json", b"answers.yaml", b"Answers.YML",
                         b"notes.bin"])


@settings(max_examples=40, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(name=names, filename=files, content=contents, flat=st.booleans())
def test_any_submission_goes_through_the_whole_pipeline(plan, name, filename, content, flat):
    root = tempfile.mkdtemp()
    try:
        broot = os.fsencode(root)
        subs = os.path.join(broot, b"subs")
        os.mkdir(subs)
        if flat:
            entry = name + b"." + filename.rsplit(b".", 1)[1]
            with open(os.path.join(subs, entry), "wb") as handle:
                handle.write(content)
        else:
            os.mkdir(os.path.join(subs, name))
            with open(os.path.join(subs, name, filename), "wb") as handle:
                handle.write(content)
        submissions = read_submissions(os.fsdecode(subs), keys=plan.keys)
        report = grade_plan(plan, submissions)
        out = os.path.join(root, "out")
        written = write_outputs(report, out).report
        data = json.loads(open(os.path.join(out, "results.json"), "rb").read().decode("utf-8"))
        ids = [s["id"] for s in data["students"]]
        skipped = [e["path"] for e in data["skipped"]]
        shown = clean_text(os.fsdecode(entry if flat else name))
        assert shown in skipped or any(shown.startswith(i) for i in ids), (shown, ids, skipped)
        assert written.internal_errors == ()
        grades = open(os.path.join(out, "grades.csv"), "rb").read().decode("utf-8")
        rows = list(csv.reader(io.StringIO(grades, newline="")))
        assert sorted(r[0] for r in rows[1:]) == sorted(safe_cell(i) for i in ids)
        pages = sorted(os.listdir(os.path.join(out, "feedback")))
        assert pages == sorted(f"{n}{s}" for n in feedback_names(report) for s in (".html", ".md"))
    finally:
        shutil.rmtree(root, ignore_errors=True)
