#!/usr/bin/python3
"""The campaign workflow (scripts/campaign/, docs/CAMPAIGNS.md) end to end:
two tiny surveys simulated into a campaign folder, `snakemake --cores 2`, and
the campaign table checked: two rows, every step ok, each row's stage times
from its run.yaml and its metrics exactly as its metrics.json gives them, and
each run's report written.

  campaign_workflow_test.py --hsmap build/tools/hsmap --source .
"""

import argparse
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile

import yaml


def fail(message):
    print(f"FAIL: {message}")
    sys.exit(1)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--hsmap", required=True)
    parser.add_argument("--source", required=True)
    args = parser.parse_args()
    snakemake = shutil.which("snakemake")
    if snakemake is None:
        fail("snakemake is not installed: scripts/setup.sh installs Debian's snakemake")

    with tempfile.TemporaryDirectory(prefix="hsmap-campaign-") as temp:
        campaign = os.path.join(temp, "cruise")
        out = os.path.join(temp, "out")
        for dive in ("dive1", "dive2"):
            subprocess.run([args.hsmap, "simulate", "--preset", "tiny", "--out", os.path.join(campaign, dive)],
                           check=True, stdout=subprocess.DEVNULL)
        os.makedirs(os.path.join(campaign, "notes"))  # a folder without survey.yaml is not a survey
        command = [snakemake, "-s", os.path.join(args.source, "scripts/campaign/Snakefile"), "--cores", "2",
                   "--directory", temp, "--config", f"campaign={campaign}", f"out={out}",
                   f"hsmap={os.path.abspath(args.hsmap)}", "variant=sequential", "threads=1"]
        result = subprocess.run(command, capture_output=True, text=True)
        if result.returncode != 0:
            fail(f"snakemake exited with {result.returncode}:\n{result.stdout}\n{result.stderr}")

        with open(os.path.join(out, "campaign.csv"), newline="", encoding="utf-8") as f:
            rows = list(csv.DictReader(f))
        if [row["survey"] for row in rows] != ["dive1", "dive2"]:
            fail(f"expected the rows dive1 and dive2, got {[row['survey'] for row in rows]}")
        for row in rows:
            run = os.path.join(out, "runs", row["survey"])
            for step in ("status", "run", "evaluate", "report"):
                if row[step] != "ok":
                    fail(f"{row['survey']}: {step} is '{row[step]}', expected ok")
            with open(os.path.join(run, "metrics.json"), encoding="utf-8") as f:
                metrics = json.load(f)
            for key in ("rgb_ate_m", "mesh_accuracy_m", "ortho_pixel_error_m", "ortho_coverage"):
                if row[key] != repr(metrics[key]):
                    fail(f"{row['survey']}: {key} is '{row[key]}' in campaign.csv, {metrics[key]!r} in metrics.json")
            with open(os.path.join(run, "run.yaml"), encoding="utf-8") as f:
                record = yaml.safe_load(f)
            for stage in record["stages"]:
                if row[f"time_s.{stage['name']}"] != repr(stage["time_s"]):
                    fail(f"{row['survey']}: time_s.{stage['name']} differs from run.yaml")
            if not os.path.isfile(row["report_path"]):
                fail(f"{row['survey']}: no report at {row['report_path']}")
        with open(os.path.join(out, "campaign.md"), encoding="utf-8") as f:
            markdown = f.read()
        if "| dive1 | sequential | ok |" not in markdown or "2 of 2 surveys ok." not in markdown:
            fail(f"campaign.md lacks its rows:\n{markdown}")
    print("campaign workflow: 2 surveys, campaign.csv and campaign.md checked")
    return 0


if __name__ == "__main__":
    sys.exit(main())
