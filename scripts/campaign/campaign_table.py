#!/usr/bin/python3
"""The campaign table of the hsmap campaign workflow (docs/CAMPAIGNS.md).

  campaign_table.py --campaign DIR --out OUT --variant V --surveys S1 S2 ...

Writes OUT/campaign.csv and OUT/campaign.md, one row per survey: the status
of its run, evaluation and report (from OUT/status/, with the last error line
of the step's log when it failed), the stage times of OUT/runs/SURVEY/run.yaml
and the key metrics of OUT/runs/SURVEY/metrics.json, copied as the file gives
them (numbers in shortest round-trip form; empty when null, absent or not
evaluated). Each file is written under a temporary name, then renamed.
Debian's python3 and python3-yaml (a dependency of snakemake) only.
"""

import argparse
import csv
import io
import json
import os
import sys

import yaml

# The metrics a campaign table shows (docs/EVALUATE.md defines each).
KEY_METRICS = [
    "rgb_ate_m", "rgb_ate_aligned_m", "uhi_position_rmse_m", "extrinsic_rotation_error_deg",
    "time_offset_error_s", "mesh_accuracy_m", "mesh_completeness", "ortho_pixel_error_m", "ortho_coverage",
]


def read_text(path):
    try:
        with open(path, encoding="utf-8") as f:
            return f.read()
    except OSError:
        return None


def last_error(log):
    """The last 'error: ...' line of a step's log, without 'error: '."""
    text = read_text(log) or ""
    errors = [line[len("error: "):] for line in text.splitlines() if line.startswith("error: ")]
    return errors[-1] if errors else ""


def step_status(out, survey, step):
    """'ok', 'failed: <why>', 'skipped: <why>' or '' (the step does not apply)."""
    status = read_text(os.path.join(out, "status", f"{survey}.{step}"))
    if status is None:
        return ""
    status = status.strip()
    if status == "0":
        return "ok"
    if status.startswith("skipped"):
        return status
    why = last_error(os.path.join(out, "logs", f"{survey}.{step}.log"))
    return f"failed: {why}" if why else f"failed: hsmap {step} exited with status {status}"


def number(value):
    """A JSON number as metrics.json wrote it (repr is Python's shortest round trip)."""
    if value is None:
        return ""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"expected a number or null, got {value!r}")
    return repr(value)


def survey_row(campaign, out, survey, variant):
    run = os.path.join(out, "runs", survey)
    has_truth = os.path.isdir(os.path.join(campaign, survey, "truth"))
    row = {"survey": survey, "variant": variant}
    row["run"] = step_status(out, survey, "run")
    row["evaluate"] = step_status(out, survey, "evaluate") if has_truth else "no truth/"
    row["report"] = step_status(out, survey, "report")
    row["status"] = "ok" if row["run"] == "ok" and row["evaluate"] in ("ok", "no truth/") else "failed"
    row["report_path"] = os.path.join(run, "report", "index.html") if row["report"] == "ok" else ""
    stages = {}
    run_yaml = os.path.join(run, "run.yaml")
    if os.path.isfile(run_yaml):
        with open(run_yaml, encoding="utf-8") as f:
            record = yaml.safe_load(f)
        for stage in record.get("stages") or []:
            stages[str(stage["name"])] = stage["time_s"]
        stages["total"] = record.get("total_time_s")
    metrics = {}
    metrics_json = os.path.join(run, "metrics.json")
    if row["evaluate"] == "ok" and os.path.isfile(metrics_json):
        with open(metrics_json, encoding="utf-8") as f:
            # Floats parsed as Python floats: repr gives back the file's digits.
            metrics = json.load(f)
    return row, stages, metrics


def write_atomically(path, text):
    partial = path + ".partial"
    with open(partial, "w", encoding="utf-8", newline="") as f:
        f.write(text)
    os.replace(partial, path)


def significant(text):
    return "" if text == "" else f"{float(text):.4g}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--campaign", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--variant", required=True)
    parser.add_argument("--surveys", nargs="+", required=True)
    args = parser.parse_args()

    rows = [survey_row(args.campaign, args.out, s, args.variant) for s in args.surveys]
    stage_names = []
    for _, stages, _ in rows:
        for name in stages:
            if name != "total" and name not in stage_names:
                stage_names.append(name)
    status_columns = ["survey", "variant", "status", "run", "evaluate", "report"]
    time_columns = [f"time_s.{name}" for name in stage_names] + ["total_time_s"]
    header = status_columns + time_columns + KEY_METRICS + ["report_path"]

    table = []
    for row, stages, metrics in rows:
        line = [row[c] for c in status_columns]
        line += [number(stages.get(name)) for name in stage_names] + [number(stages.get("total"))]
        line += [number(metrics.get(key)) for key in KEY_METRICS]
        line.append(row["report_path"])
        table.append(line)

    text = io.StringIO()
    writer = csv.writer(text, lineterminator="\n")
    writer.writerow(header)
    writer.writerows(table)
    write_atomically(os.path.join(args.out, "campaign.csv"), text.getvalue())

    numeric = set(time_columns + KEY_METRICS)
    md = [f"# hsmap campaign: {os.path.basename(os.path.normpath(args.campaign))}", "",
          f"Campaign `{args.campaign}`, variant `{args.variant}`, {len(rows)} surveys; each run in "
          f"`{os.path.join(args.out, 'runs', 'SURVEY')}`, each step's log in "
          f"`{os.path.join(args.out, 'logs', 'SURVEY.STEP.log')}`. Times in seconds; the metrics as "
          "docs/EVALUATE.md defines them (empty: not evaluated, or not applicable).", ""]
    shown = [c for c in header if c != "report_path"]
    md.append("| " + " | ".join(shown) + " |")
    md.append("|" + "|".join("---:" if c in numeric else "---" for c in shown) + "|")
    for line in table:
        cells = []
        for column, value in zip(header, line):
            if column == "report_path":
                continue
            cell = significant(value) if column in numeric else value
            cells.append(cell.replace("|", "\\|").replace("\n", " "))
        md.append("| " + " | ".join(cells) + " |")
    failed = sum(1 for line in table if line[2] != "ok")
    md += ["", f"{len(table) - failed} of {len(table)} surveys ok."]
    write_atomically(os.path.join(args.out, "campaign.md"), "\n".join(md) + "\n")
    print(f"campaign: wrote {os.path.join(args.out, 'campaign.csv')} and campaign.md: "
          f"{len(table) - failed} of {len(table)} surveys ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
