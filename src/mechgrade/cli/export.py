"""``mechgrade export``: results.json to LMS files and spreadsheets."""

from __future__ import annotations

from pathlib import Path

import click

from ..errors import ExportError, Location
from ..export import EXPORTERS, ExportOptions, read_results
from ..export.options import MissingGrade, MoodleKey, Visibility
from ..outfolder import OutputKind
from .common import (claim_out, main, output_lines, reports_errors, run_arguments,
                     run_inputs, say)

GRADESCOPE_FOLDER = OutputKind("mechgrade export", None, ("*.json",))
"""What ``export --format gradescope`` of several students writes into ``--out`` (a folder
written before manifests existed is not recognised: its files are named by students' ids)."""

LMS_FORMATS = ("canvas", "moodle")
DEFAULT_OUT = {
    "canvas": "canvas_import.csv",
    "moodle": "moodle_import.csv",
    "gradescope": "results.json",
    "grades-csv": "grades.csv",
    "long-csv": "results.csv",
    "json": "results.export.json",
}


@main.command("export")
@click.argument("results_json", type=click.Path(dir_okay=True, path_type=Path))
@click.option("--format", "fmt", required=True, type=click.Choice(list(EXPORTERS)),
              help="Output format.")
@click.option("--roster", type=click.Path(path_type=Path), default=None,
              help="Class roster: Canvas gradebook export, Moodle grades export or id,name CSV.")
@click.option("--out", type=click.Path(path_type=Path), default=None,
              help="Output file (default depends on the format).")
@click.option("--missing", type=click.Choice([m.value for m in MissingGrade]), default="zero",
              show_default=True, help="Grade written for a student without a submission.")
@click.option("--excel-bom", is_flag=True, help="Start CSV files with a UTF-8 BOM for Excel.")
@click.option("--no-points-possible", is_flag=True,
              help="Canvas: leave out the 'Points Possible' row.")
@click.option("--moodle-key", type=click.Choice([k.value for k in MoodleKey]), default="email",
              show_default=True, help="Moodle: the column Moodle maps users by.")
@click.option("--visibility", type=click.Choice([v.value for v in Visibility]),
              default="visible", show_default=True, help="Gradescope: visibility of the tests.")
@click.option("--canvas-assignment", default=None, metavar="TITLE_OR_ID",
              help="Canvas: the assignment column to fill, as 'Title (12345)', its title or "
                   "its Canvas id (default: picked from a Canvas gradebook roster).")
@click.option("--replace-existing", is_flag=True,
              help="Canvas, Moodle: replace grades already in the LMS (the roster's cells) that "
                   "differ from mechgrade's; by default they are kept and listed.")
@click.option("--scale-to", type=float, default=None, metavar="POINTS",
              help="Canvas, Moodle: scale the grades to the LMS assignment's points.")
@click.option("--dry-run", is_flag=True,
              help="Canvas, Moodle: write nothing; list what the import would change.")
@reports_errors
def export_command(results_json: Path, fmt: str, roster: Path | None, out: Path | None,
                   missing: str, excel_bom: bool, no_points_possible: bool, moodle_key: str,
                   visibility: str, canvas_assignment: str | None, replace_existing: bool,
                   scale_to: float | None, dry_run: bool) -> None:
    """Export RESULTS_JSON (written by 'mechgrade grade') for an LMS or a spreadsheet."""
    from ..export.changes import Notice
    from ..export.gradescope import writes_folder  # imported here, as the exporters are
    from ..roster import read_roster  # imported here: 'export --help' needs no roster reader

    for flag, given in (("--replace-existing", replace_existing),
                        ("--scale-to", scale_to is not None), ("--dry-run", dry_run)):
        if given and fmt not in LMS_FORMATS:
            raise ExportError(f"expected {flag} only with --format canvas or moodle (the "
                              f"formats compared with an LMS's grades), found --format {fmt}",
                              where=Location(field=flag.lstrip("-").replace("-", "_")))

    report = read_results(results_json)
    class_roster = read_roster(roster) if roster is not None else None
    out = out if out is not None else Path(DEFAULT_OUT[fmt])
    if out.exists() and out.resolve() == results_json.resolve():
        raise ExportError(f"{out}: expected an output path other than the results file itself")
    options = ExportOptions(missing=MissingGrade(missing), excel_bom=excel_bom,
                            points_possible=not no_points_possible,
                            gradescope_visibility=Visibility(visibility),
                            moodle_key=MoodleKey(moodle_key),
                            canvas_assignment=canvas_assignment,
                            replace_existing=replace_existing, dry_run=dry_run,
                            scale_to=scale_to)
    folder = claim_out(out, GRADESCOPE_FOLDER) if fmt == "gradescope" and \
        writes_folder(report) else None
    messages = EXPORTERS[fmt](report, out if folder is None else folder.staging,
                              roster=class_roster, options=options)
    done = folder.commit(run_arguments(), inputs=run_inputs(results=results_json,
                                                            roster=roster)) \
        if folder is not None else None
    if class_roster is not None:
        for line, reason in class_roster.skipped:
            say(f"warning: {roster}:{line}: skipped {reason}", err=True)
    for message in messages:
        if not isinstance(message, Notice):
            say(f"warning: {message}", err=True)
    for failing in report.failing_expects:
        say(f"warning: graded although the problem fails this expect: test "
            f"(--accept-failing-expect): {failing}", err=True)
    for message in messages:
        if isinstance(message, Notice):
            say(str(message))
    if not dry_run:
        say(f"wrote {fmt} export of {len(report.students)} "
            f"{'result' if len(report.students) == 1 else 'results'} to {out}")
    for text in output_lines(done) if done is not None else ():
        say(text)

