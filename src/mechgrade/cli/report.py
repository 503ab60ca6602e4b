"""``mechgrade report``: the class report of a results.json, as one HTML file."""

from __future__ import annotations

from pathlib import Path

import click

from .common import main, reports_errors, say


@main.command("report")
@click.argument("results_json", type=click.Path(dir_okay=True, path_type=Path))
@click.option("--out", type=click.Path(path_type=Path), default=Path("class_report.html"),
              show_default=True, help="HTML file to write.")
@reports_errors
def report_command(results_json: Path, out: Path) -> None:
    """Write the class report of RESULTS_JSON as one self-contained HTML file."""
    # here, not at the top: `report --help` loads neither the exporters nor matplotlib
    from ..export import read_results
    from ..report.class_report import write_class_report

    report = read_results(results_json)
    write_class_report(report, out)
    say(f"wrote class report of {len(report.students)} students to {out}")
