#!/usr/bin/python3
"""Measure hsmap's figures and write docs/BENCHMARKS.md.

Usage:
  benchmarks/benchmarks_page.py --build BUILD_DIR --work WORK_DIR
      [--surveys NAME ...] [--only SECTION ...] [--repeats N] [--threads N]
      [--display-build DIR] [--from-work] [--page FILE]

Simulates the preset surveys it needs into WORK/surveys/NAME (skipped when
WORK/surveys/NAME/survey.yaml exists), runs the measured commands one at a
time (hsmap run under /usr/bin/time -v, hsmap evaluate, the Google Benchmark
programs of BUILD/benchmarks/ with --benchmark_format=json), stores each
measurement's raw result as JSON in WORK/results/ (logs in WORK/logs/) and
writes the page: one section per stage or topic, one table each, with the
columns figure | goal | value | command | commit.

  --only SECTION ...   measure these sections only; the others keep the
                       values stored in WORK (each row names its commit)
  --surveys NAME ...   measure on these presets only (default: all of
                       tiny rugged flat low-relief transect-100m); figures of
                       the others keep the values stored in WORK
  --from-work          measure nothing: write the page from WORK/results/
  --repeats N          repeats of each speed measurement (median quoted; 3)
  --threads N          pass --threads N to every hsmap run
  --display-build DIR  how the build folder is written in the page's commands
                       (default: BUILD_DIR, relative to the repository root
                       when inside it); e.g. `build` when BUILD_DIR is a copy

A figure that could not be produced shows "not measured" or "failed: <first
line of stderr>"; a metric that is null in metrics.json shows "null" with
the reason hsmap evaluate printed. Debian's /usr/bin/python3, standard
library only. Sections: see SECTIONS below, or --help.
"""
import argparse
import datetime
import json
import os
import re
import shlex
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
PRESETS = ["tiny", "rugged", "flat", "low-relief", "transect-100m"]
VARIANTS = ["stacked", "planar", "sequential", "joint"]
SECTIONS = ["simulate", "inspect", "frontend", "georef", "scale", "surface", "refine", "joint", "variants",
            "compare", "resume", "products", "tiny", "unlike", "kernels", "io"]
# Surveys written from a configuration rather than a preset (section
# `scale`): few INS fixes, and tracking losses.
CONFIG_SURVEYS = {
    "short": "benchmarks/short_survey.yaml",
    "short-no-attitude": "benchmarks/short_survey_no_attitude.yaml",
    "rugged-black-frames": "benchmarks/rugged_black_frames.yaml",
    "rugged-blackout-2s": "benchmarks/rugged_blackout_2s.yaml",
}
TIME = "/usr/bin/time"

# ---------------------------------------------------------------- helpers


def log(text):
    print(f"[{datetime.datetime.now():%H:%M:%S}] {text}", flush=True)


def median(values):
    values = [v for v in values if v is not None]
    return statistics.median(values) if values else None


def first_error_line(text):
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    for line in lines:
        if line.lower().startswith("error") or " error:" in line.lower():
            return line
    return lines[0] if lines else ""


def git(*args):
    try:
        return subprocess.run(["git", "-C", str(REPO), *args], capture_output=True, text=True,
                              check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return ""


def commit_label():
    head = git("rev-parse", "--short", "HEAD") or "unknown"
    dirty = bool(git("status", "--porcelain", "--untracked-files=no"))
    return head, dirty


def machine():
    cpu = ""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    mem_gb = 0.0
    try:
        for line in Path("/proc/meminfo").read_text().splitlines():
            if line.startswith("MemTotal:"):
                mem_gb = int(line.split()[1]) / 1048576
    except OSError:
        pass
    return {"nproc": os.cpu_count(), "memory_gb": round(mem_gb, 1), "cpu": cpu,
            "kernel": os.uname().release}


def parse_time_v(text):
    """Wall s, CPU s, peak MB and exit status from GNU time -v's report."""
    out = {"wall_s": None, "cpu_s": None, "peak_mb": None}
    cpu = 0.0
    for line in text.splitlines():
        line = line.strip()
        if line.startswith("Elapsed (wall clock)"):
            seconds = 0.0
            for part in line.rsplit(": ", 1)[1].split(":"):
                seconds = seconds * 60 + float(part)
            out["wall_s"] = seconds
        elif line.startswith("User time") or line.startswith("System time"):
            cpu += float(line.rsplit(": ", 1)[1])
            out["cpu_s"] = cpu
        elif line.startswith("Maximum resident set size"):
            out["peak_mb"] = int(line.rsplit(": ", 1)[1]) / 1024
    return out


def md(text):
    return str(text).replace("|", "\\|")


def code(text):
    return "`" + str(text).replace("|", "\\|") + "`"


# ---------------------------------------------------------------- context


class Ctx:
    def __init__(self, args):
        self.args = args
        # Without --build (--from-work) the commands are written for REPO/build.
        self.build = Path(args.build).resolve() if args.build else REPO / "build"
        self.work = Path(args.work).resolve()
        self.results_dir = self.work / "results"
        self.logs_dir = self.work / "logs"
        self.repeats = max(1, args.repeats)
        if args.display_build:
            self.display_build = args.display_build.rstrip("/")
        else:
            self.display_build = None
            self.display_build = self.path(self.build)
        self.commit, self.dirty = commit_label()
        self.results = {}
        self.attempted = set()

    def path(self, p):
        """A path as the page writes it: relative to the repository root when inside it."""
        p = Path(p)
        if self.display_build and str(p).startswith(str(self.build)):
            return self.display_build + str(p)[len(str(self.build)):]
        try:
            return str(p.resolve().relative_to(REPO))
        except ValueError:
            return str(p)

    def hsmap(self):
        return self.build / "tools" / "hsmap"

    def bench(self, name):
        return self.build / "benchmarks" / name

    def survey(self, name):
        return self.work / "surveys" / name

    def run_dir(self, survey, variant):
        return self.work / "runs" / f"{survey}-{variant}"

    def show(self, argv):
        return " ".join(shlex.quote(self.path(a)) if ("/" in str(a) and not str(a).startswith("--"))
                        else shlex.quote(str(a)) for a in argv)

    # -- results
    def load_results(self):
        if not self.results_dir.is_dir():
            return
        for f in sorted(self.results_dir.glob("*.json")):
            try:
                data = json.loads(f.read_text())
                self.results[data["id"]] = data
            except (OSError, ValueError, KeyError) as failure:
                log(f"warning: {f} unreadable ({failure}); ignored")

    def save(self, mid, data):
        data = dict(data)
        data["id"] = mid
        data.setdefault("commit", self.commit + ("+dirty" if self.dirty else ""))
        data.setdefault("date_utc", datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"))
        data.setdefault("machine", machine())
        self.results_dir.mkdir(parents=True, exist_ok=True)
        target = self.results_dir / (mid.replace("/", "__") + ".json")
        tmp = target.with_suffix(".json.partial")
        tmp.write_text(json.dumps(data, indent=1, sort_keys=True) + "\n")
        tmp.replace(target)
        self.results[mid] = data
        self.attempted.add(mid)
        return data

    # -- commands
    def execute(self, argv, name, timed=True, stdout_to=None, env=None):
        """Runs argv (under /usr/bin/time -v when timed); logs to WORK/logs/name.*."""
        self.logs_dir.mkdir(parents=True, exist_ok=True)
        out_path = self.logs_dir / f"{name}.out"
        err_path = self.logs_dir / f"{name}.err"
        time_path = self.logs_dir / f"{name}.time"
        argv = [str(a) for a in argv]
        full = ([TIME, "-v", "-o", str(time_path)] if timed else []) + argv
        log(f"running: {self.show(argv)}")
        start = time.monotonic()
        try:
            with open(stdout_to or out_path, "w") as out, open(err_path, "w") as err:
                rc = subprocess.run(full, stdout=out, stderr=err, env=env).returncode
        except OSError as failure:
            err_path.write_text(str(failure) + "\n")
            rc = 127
        elapsed = time.monotonic() - start
        result = {"rc": rc, "wall_s": elapsed, "cpu_s": None, "peak_mb": None,
                  "stdout": "" if stdout_to else out_path.read_text(errors="replace"),
                  "stderr": err_path.read_text(errors="replace")}
        if timed and time_path.exists():
            measured = parse_time_v(time_path.read_text(errors="replace"))
            for key in ("wall_s", "cpu_s", "peak_mb"):
                if measured[key] is not None:
                    result[key] = measured[key]
        if rc != 0:
            result["error"] = "failed: " + (first_error_line(result["stderr"]) or f"exit status {rc}")
        log(f"  {'ok' if rc == 0 else 'FAILED (' + result['error'] + ')'} in {elapsed:.1f} s"
            + (f", peak {result['peak_mb']:.0f} MB" if result["peak_mb"] else ""))
        return result


class Skip(Exception):
    """A measurement that cannot run; its message says why."""


# ---------------------------------------------------------------- measurements
# Each measurement has an id ("run/rugged/joint"), a function that runs it and
# stores its JSON, and the command(s) the page shows for it.


def need_build(ctx, path):
    if not Path(path).exists():
        raise Skip(f"not measured: {ctx.path(path)} not found (build it)")


def ensure_survey(ctx, name):
    survey = ctx.survey(name)
    if (survey / "survey.yaml").exists():
        return survey
    sim = ctx.results.get(f"simulate/{name}")
    if f"simulate/{name}" in ctx.attempted and sim and not sim.get("ok"):
        raise Skip(f"not measured: the survey {name} could not be simulated ({sim.get('error')})")
    measure_simulate(ctx, name)
    if not (survey / "survey.yaml").exists():
        raise Skip(f"not measured: the survey {name} could not be simulated "
                   f"({ctx.results.get(f'simulate/{name}', {}).get('error', '')})")
    return survey


# A survey unlike the presets, as other programs write them: another camera
# (800 x 600, strong radial-tangential distortion) and UHI (480 samples x 40
# bands), the INS without its attitude columns, the cube rewritten big-endian
# BIP (scripts/rewrite_cube.py).
UNLIKE_CONFIG = "benchmarks/frontend_unlike_presets.yaml"


def simulate_argv(ctx, name):
    if name == "unlike":
        return [ctx.hsmap(), "simulate", "--config", REPO / UNLIKE_CONFIG, "--out", ctx.survey(name)]
    if name in CONFIG_SURVEYS:
        return [ctx.hsmap(), "simulate", "--config", REPO / CONFIG_SURVEYS[name], "--out", ctx.survey(name)]
    return [ctx.hsmap(), "simulate", "--preset", name, "--out", ctx.survey(name)]


def unlike_rewrites(ctx, survey):
    """The INS's attitude columns cut; the cube rewritten big-endian BIP. Returns an error text or None."""
    ins = survey / "nav" / "ins.csv"
    lines = ins.read_text().splitlines()
    ins.write_text("\n".join(",".join(line.split(",")[:4]) for line in lines) + "\n")
    r = ctx.execute(["/usr/bin/python3", REPO / "scripts" / "rewrite_cube.py", survey, "--interleave", "bip",
                     "--byte-order", "1"], "simulate_unlike_rewrite", timed=False)
    return None if r["rc"] == 0 else r.get("error")


def measure_simulate(ctx, name):
    mid = f"simulate/{name}"
    survey = ctx.survey(name)
    if (survey / "survey.yaml").exists():
        log(f"{ctx.path(survey)} exists: not simulated again (delete it to time the simulation)")
        return
    need_build(ctx, ctx.hsmap())
    shutil.rmtree(survey, ignore_errors=True)
    survey.parent.mkdir(parents=True, exist_ok=True)
    r = ctx.execute(simulate_argv(ctx, name), f"simulate_{name}")
    if r["rc"] == 0 and name == "unlike":
        r["error"] = unlike_rewrites(ctx, survey)
        if r["error"]:
            r["rc"] = 1
            (survey / "survey.yaml").unlink(missing_ok=True)
    ctx.save(mid, {"ok": r["rc"] == 0, "error": r.get("error"), "wall_s": [r["wall_s"]],
                   "peak_mb": [r["peak_mb"]], "cpu_s": r["cpu_s"],
                   "command": "/usr/bin/time -v " + ctx.show(simulate_argv(ctx, name))})


def run_argv(ctx, survey, variant, extra=()):
    argv = [ctx.hsmap(), "run", ctx.survey(survey), "--out", ctx.run_dir(survey, variant), "--variant", variant]
    if variant != "stacked":
        argv.append("--no-geotiff")  # the GeoTIFFs change no metric; stacked has no products options
    if ctx.args.threads is not None:
        argv += ["--threads", str(ctx.args.threads)]
    if survey == "transect-100m" and variant in ("sequential", "joint"):
        # As measured since 2026-12: 1 cm pixels (a quarter of the 15 GB ortho-image), no point cloud,
        # two joint rounds.
        argv += ["--no-points", "--ortho-pixel", "0.01"] + (["--joint-rounds", "2"] if variant == "joint" else [])
    return argv + list(extra)


def evaluate_argv(ctx, survey, variant):
    return [ctx.hsmap(), "evaluate", ctx.run_dir(survey, variant), "--truth", ctx.survey(survey) / "truth"]


def parse_evaluate_table(text):
    """{metric: reason} for the null metrics of hsmap evaluate's printed table."""
    reasons = {}
    header = None
    for line in text.splitlines():
        if line.startswith("metric ") and " value" in line:
            header = line
            continue
        if header is None or not line.strip():
            continue
        parts = line.split()
        if len(parts) < 2 or parts[1] != "null":
            continue
        key = parts[0]
        # The reason follows the "INS floor" column, which holds a value only beside
        # rgb_ate_m and rgb_scale_error (printMetricsTable in pipelines/evaluate/).
        start = header.find("INS floor")
        rest = line[start:].strip() if 0 <= start < len(line) else ""
        if key in ("rgb_ate_m", "rgb_scale_error") and rest:
            rest = rest.split(None, 1)[1] if len(rest.split(None, 1)) > 1 else ""
        reason = rest.strip()
        reasons[key] = reason
    return reasons


def read_stage_times(run_yaml):
    stages = {}
    try:
        text = Path(run_yaml).read_text()
    except OSError:
        return stages
    for m in re.finditer(r"\{name: ([\w-]+), time_s: ([0-9.eE+-]+), peak_rss_mb: ([0-9.eE+-]+)\}", text):
        stages[m.group(1)] = {"time_s": float(m.group(2)), "peak_rss_mb": float(m.group(3))}
    return stages


def measure_run(ctx, survey, variant):
    mid = f"run/{survey}/{variant}"
    need_build(ctx, ctx.hsmap())
    ensure_survey(ctx, survey)
    run = ctx.run_dir(survey, variant)
    shutil.rmtree(run, ignore_errors=True)
    run.parent.mkdir(parents=True, exist_ok=True)
    argv = run_argv(ctx, survey, variant)
    r = ctx.execute(argv, f"run_{survey}_{variant}")
    data = {"ok": r["rc"] == 0, "error": r.get("error"), "wall_s": [r["wall_s"]], "peak_mb": [r["peak_mb"]],
            "cpu_s": r["cpu_s"], "command": ctx.show(argv),
            "evaluate_command": ctx.show(evaluate_argv(ctx, survey, variant)),
            "stages": read_stage_times(run / "run.yaml"),
            "frontend_summary": next((l for l in r["stdout"].splitlines() if l.startswith("front-end: ")), None)}
    if r["rc"] == 0:
        e = ctx.execute(evaluate_argv(ctx, survey, variant), f"evaluate_{survey}_{variant}", timed=False)
        data["evaluate_ok"] = e["rc"] == 0
        data["evaluate_error"] = e.get("error")
        data["null_reasons"] = parse_evaluate_table(e["stdout"])
        try:
            data["metrics"] = json.loads((run / "metrics.json").read_text())
        except (OSError, ValueError) as failure:
            data["evaluate_ok"] = False
            data["evaluate_error"] = data["evaluate_error"] or f"failed: RUN/metrics.json unreadable ({failure})"
    ctx.save(mid, data)


def measure_resume(ctx, survey, variant):
    mid = f"resume/{survey}/{variant}"
    need_build(ctx, ctx.hsmap())
    run = ctx.run_dir(survey, variant)
    base = ctx.results.get(f"run/{survey}/{variant}")
    if not base or not base.get("ok") or not (run / "run.yaml").exists():
        ctx.save(mid, {"ok": False, "error": f"not measured: no finished {variant} run of {survey} in WORK",
                       "command": "/usr/bin/time -v " + ctx.show(run_argv(ctx, survey, variant))})
        return
    argv = run_argv(ctx, survey, variant)
    walls, peaks, error = [], [], None
    for i in range(ctx.repeats):
        r = ctx.execute(argv, f"resume_{survey}_{variant}_{i + 1}")
        if r["rc"] != 0:
            error = r["error"]
            break
        text = r["stdout"] + r["stderr"]
        rerun = re.findall(r"stage (\w+): runs again", text)
        if rerun or "up to date, skipped" not in text:
            error = "failed: stages ran again: " + (", ".join(rerun) or "no stage said 'up to date, skipped'")
            break
        walls.append(r["wall_s"])
        peaks.append(r["peak_mb"])
    ctx.save(mid, {"ok": error is None, "error": error, "wall_s": walls, "peak_mb": peaks,
                   "command": "/usr/bin/time -v " + ctx.show(argv) + "   # on the finished run folder"})


def measure_restart(ctx, survey, variant):
    """benchmarks/resume_benchmark.sh: a full run with --threads 1, then --from each stage, each compared byte
    for byte with the full run's products. Its Markdown table in WORK/restart/SURVEY_VARIANT.md is reused when
    present (the script takes the sum of all the stages' times)."""
    mid = f"restart/{survey}/{variant}"
    need_build(ctx, ctx.hsmap())
    path = ensure_survey(ctx, survey)
    table = ctx.work / "restart" / f"{survey}_{variant}.md"
    script = Path(__file__).resolve().parent / "resume_benchmark.sh"
    build = Path(ctx.hsmap()).resolve().parent.parent
    command = f"WORK_DIR=/tmp benchmarks/resume_benchmark.sh {ctx.show([path])} {variant} -- {ctx.display_build}"
    if table.exists():
        limited = re.search(r"^<!-- STAGES=(.*) -->$", table.read_text(), re.M)
        if limited:
            command = f"STAGES=\"{limited.group(1)}\" " + command
    if not table.exists():
        table.parent.mkdir(parents=True, exist_ok=True)
        env = dict(os.environ, WORK_DIR=str(ctx.work / "restart"))
        r = ctx.execute(["bash", script, path, variant, "--", build], f"restart_{survey}_{variant}", timed=False,
                        stdout_to=table, env=env)
        if r["rc"] != 0:
            table.unlink(missing_ok=True)
            ctx.save(mid, {"ok": False, "error": r["error"], "command": command})
            return
    rows = {}
    for line in table.read_text().splitlines():
        m = re.match(r"\| `--from (\w+)` \| ([0-9.]+) \| (.*) \|$", line)
        if m:
            rows[m.group(1)] = {"wall_s": float(m.group(2)), "result": m.group(3)}
    ctx.save(mid, {"ok": bool(rows), "error": None if rows else "failed: no --from row in " + str(table),
                   "stages": rows, "command": command})


def compare_argv(ctx, survey):
    return [ctx.hsmap(), "compare", ctx.survey(survey), "--out", ctx.work / "compare" / survey, "--force"]


def measure_compare(ctx, survey):
    """`hsmap compare` of the four variants, timed once; each variant's time from its progress line."""
    mid = f"compare/{survey}"
    need_build(ctx, ctx.hsmap())
    ensure_survey(ctx, survey)
    argv = compare_argv(ctx, survey)
    r = ctx.execute(argv, f"compare_{survey}")
    variants = {}
    for line in r["stdout"].splitlines():
        m = re.match(r"\[(\w+)\] ok in ([0-9.]+) s", line)
        if m:
            variants[m.group(1)] = float(m.group(2))
    ctx.save(mid, {"ok": r["rc"] == 0, "error": r.get("error"), "wall_s": [r["wall_s"]], "peak_mb": [r["peak_mb"]],
                   "variants": variants, "command": "/usr/bin/time -v " + ctx.show(argv)})


def measure_inspect(ctx, survey):
    mid = f"inspect/{survey}"
    need_build(ctx, ctx.hsmap())
    path = ensure_survey(ctx, survey)
    argv = [ctx.hsmap(), "inspect", path]
    walls, peaks, error = [], [], None
    for i in range(ctx.repeats):
        r = ctx.execute(argv, f"inspect_{survey}_{i + 1}")
        if r["rc"] != 0:
            error = r["error"]
            break
        walls.append(r["wall_s"])
        peaks.append(r["peak_mb"])
    ctx.save(mid, {"ok": error is None, "error": error, "wall_s": walls, "peak_mb": peaks,
                   "command": "/usr/bin/time -v " + ctx.show(argv)})


FRONTEND_RE = re.compile(r"front-end: (\d+) of (\d+) frames posed, (\d+) keyframes, (\d+) landmarks,.*?"
                         r"(\d+) tracking loss(?:es)?; ([0-9.]+) frames/s \(tracking alone ([0-9.]+)\)")
ALIGNED_RE = re.compile(r"aligned rms ([0-9.eE+-]+) m over a ([0-9.eE+-]+) m path \(([0-9.eE+-]+) %\)")


def measure_frontend(ctx, survey):
    mid = f"frontend/{survey}"
    tool = ctx.bench("frontend_measure_tool")
    need_build(ctx, tool)
    path = ensure_survey(ctx, survey)
    argv = [tool, path]
    runs, error = [], None
    for i in range(ctx.repeats):
        r = ctx.execute(argv, f"frontend_{survey}_{i + 1}")
        if r["rc"] != 0:
            error = r["error"]
            break
        m, a = FRONTEND_RE.search(r["stdout"]), ALIGNED_RE.search(r["stdout"])
        if not m:
            error = "failed: no 'front-end: ... frames posed' summary in the tool's output"
            break
        runs.append({"posed": int(m.group(1)), "frames": int(m.group(2)), "keyframes": int(m.group(3)),
                     "landmarks": int(m.group(4)), "losses": int(m.group(5)), "fps": float(m.group(6)),
                     "tracking_fps": float(m.group(7)),
                     "aligned_rms_m": float(a.group(1)) if a else None,
                     "percent_of_path": float(a.group(3)) if a else None,
                     "wall_s": r["wall_s"], "peak_mb": r["peak_mb"]})
    ctx.save(mid, {"ok": error is None and bool(runs), "error": error, "runs": runs,
                   "command": "/usr/bin/time -v " + ctx.show(argv)})


def products_argvs(ctx, survey):
    run = ctx.run_dir(survey, "products")
    common = ["--variant", "sequential", "--no-geotiff", "--no-points", "--extrinsic-rounds", "0"]
    if ctx.args.threads is not None:
        common += ["--threads", str(ctx.args.threads)]
    prep = [ctx.hsmap(), "run", ctx.survey(survey), "--out", run, *common, "--until", "refine"]
    timed = [ctx.hsmap(), "run", ctx.survey(survey), "--out", run, *common, "--from", "products"]
    return prep, timed


def products_command(ctx, survey):
    prep, timed = products_argvs(ctx, survey)
    cube = ctx.path(ctx.survey(survey) / "uhi/cube.raw")
    return (ctx.show(prep) + f" && dd if={cube} iflag=nocache count=0 && time cat {cube} > /dev/null"
            + " && /usr/bin/time -v " + ctx.show(timed))


def measure_products(ctx, survey):
    mid = f"products/{survey}"
    need_build(ctx, ctx.hsmap())
    path = ensure_survey(ctx, survey)
    prep, timed = products_argvs(ctx, survey)
    run = ctx.run_dir(survey, "products")
    command = products_command(ctx, survey)
    r = ctx.execute(prep, f"products_{survey}_prepare")  # resumes: stages up to date are skipped
    if r["rc"] != 0:
        ctx.save(mid, {"ok": False, "error": r["error"], "command": command})
        return
    cube = path / "uhi" / "cube.raw"
    with open(path / "uhi" / "lines.csv") as f:
        lines = sum(1 for _ in f) - 1
    repeats, error = [], None
    for i in range(ctx.repeats):
        shutil.rmtree(run / "hyperspectral", ignore_errors=True)  # untimed, as a user's fresh folder
        subprocess.run(["sync"])
        subprocess.run(["dd", f"if={cube}", "iflag=nocache", "count=0", "status=none"])
        log(f"running: cat {ctx.path(cube)} > /dev/null (cube dropped from the page cache)")
        start = time.monotonic()
        with open(os.devnull, "wb") as null:
            subprocess.run(["cat", str(cube)], stdout=null)
        cat_s = time.monotonic() - start
        log(f"  ok in {cat_s:.1f} s")
        r = ctx.execute(timed, f"products_{survey}_{i + 1}")
        if r["rc"] != 0:
            error = r["error"]
            break
        stage_s = read_stage_times(run / "run.yaml").get("products", {}).get("time_s", r["wall_s"])
        repeats.append({"stage_s": stage_s, "wall_s": r["wall_s"], "peak_mb": r["peak_mb"], "cat_s": cat_s,
                        "lines_per_s": lines / stage_s if stage_s else None,
                        "stage_over_cat": stage_s / cat_s if cat_s else None,
                        "ortho_gb": (run / "hyperspectral/ortho.raw").stat().st_size / 1e9
                        if (run / "hyperspectral/ortho.raw").exists() else None})
    ctx.save(mid, {"ok": error is None and bool(repeats), "error": error, "lines": lines, "repeats": repeats,
                   "cube_gb": cube.stat().st_size / 1e9, "command": command})


GBENCH = {
    # id: (program, filter)
    "gbench/engine_ba": ("engine_bench", "BM_KeyframeBundleAdjustment/linear_solver:0"),
    "gbench/engine_spline": ("engine_bench", "BM_SplineJointCalibration/linear_solver:0"),
    "gbench/raycast": ("raycast_bench", "BM_SceneBuild/2|BM_CameraFrameBatch|BM_CameraFrameSingleRays/2"),
}


def gbench_argv(ctx, mid):
    program, flt = GBENCH[mid]
    return [ctx.bench(program), f"--benchmark_filter={flt}", f"--benchmark_repetitions={ctx.repeats}",
            "--benchmark_report_aggregates_only=true", "--benchmark_format=json"]


def measure_gbench(ctx, mid):
    argv = gbench_argv(ctx, mid)
    need_build(ctx, argv[0])
    r = ctx.execute(argv, mid.replace("/", "_"))
    data = {"ok": r["rc"] == 0, "error": r.get("error"), "peak_mb": [r["peak_mb"]],
            "command": ctx.show(argv[:-1])}
    if r["rc"] == 0:
        try:
            report = json.loads(r["stdout"])
            data["benchmarks"] = {b.get("run_name", b["name"]): b for b in report.get("benchmarks", [])
                                  if b.get("aggregate_name", "median") == "median"}
            data["context"] = report.get("context", {})
        except ValueError as failure:
            data.update(ok=False, error=f"failed: JSON output unreadable ({failure})")
    ctx.save(mid, data)


ENVI_SHAPE = ["--samples", "1920", "--bands", "211", "--lines", "2650"]


def envi_commands(ctx, il):
    tool = ctx.bench("envi_stream_tool")
    hdr = ctx.work / "io" / f"envi_{il}.hdr"
    write = [tool, "write", hdr, *ENVI_SHAPE, "--interleave", il, "--type", "12"]
    read = [tool, "read", hdr, "--mode", "buffered"]
    command = (ctx.show(write) + f" && cat {ctx.path(hdr.with_suffix('.raw'))} > /dev/null && /usr/bin/time -v "
               + ctx.show(read) + f" && time cat {ctx.path(hdr.with_suffix('.raw'))} > /dev/null")
    return hdr, write, read, command


def measure_envi(ctx):
    tool = ctx.bench("envi_stream_tool")
    for il in ("bil", "bip", "bsq"):
        mid = f"envi/{il}"
        try:
            need_build(ctx, tool)
        except Skip as s:
            ctx.save(mid, {"ok": False, "error": str(s)})
            continue
        d = ctx.work / "io"
        d.mkdir(parents=True, exist_ok=True)
        hdr, write, read, command = envi_commands(ctx, il)
        r = ctx.execute(write, f"envi_{il}_write", timed=False)
        if r["rc"] != 0:
            ctx.save(mid, {"ok": False, "error": r["error"], "command": command})
            continue
        ctx.execute(["cat", hdr.with_suffix(".raw")], f"envi_{il}_warm", timed=False)
        cats, reads, peaks, error = [], [], [], None
        for i in range(ctx.repeats):
            c = ctx.execute(["cat", hdr.with_suffix(".raw")], f"envi_{il}_cat_{i + 1}")
            x = ctx.execute(read, f"envi_{il}_read_{i + 1}")
            if x["rc"] != 0:
                error = x["error"]
                break
            cats.append(c["wall_s"])
            reads.append(x["wall_s"])
            peaks.append(x["peak_mb"])
        for suffix in (".hdr", ".raw"):
            hdr.with_suffix(suffix).unlink(missing_ok=True)
        (ctx.logs_dir / f"envi_{il}_warm.out").unlink(missing_ok=True)
        for i in range(ctx.repeats):
            (ctx.logs_dir / f"envi_{il}_cat_{i + 1}.out").unlink(missing_ok=True)
        ctx.save(mid, {"ok": error is None, "error": error, "cat_s": cats, "read_s": reads, "peak_mb": peaks,
                       "command": command})


def geotiff_commands(ctx):
    d = ctx.work / "io"
    hdr, tif, cog = d / "ortho.hdr", d / "ortho.tif", d / "cog.tif"
    write = [ctx.bench("geotiff_export_tool"), "write", hdr, "--lines", "4000"]
    export = [ctx.bench("geotiff_export_tool"), "export", hdr, tif]
    reference = ["gdal_translate", "-q", "-of", "COG", "-co", "COMPRESS=DEFLATE", "-co", "PREDICTOR=YES",
                 "-co", "BLOCKSIZE=512", "-co", "OVERVIEWS=AUTO", "-co", "RESAMPLING=AVERAGE",
                 "-co", "NUM_THREADS=ALL_CPUS", "-co", "BIGTIFF=IF_SAFER", hdr.with_suffix(".raw"), cog]
    command = ctx.show(write) + " && /usr/bin/time -v " + ctx.show(export)
    ref_command = ctx.show(write) + " && /usr/bin/time -v " + ctx.show(reference)
    return hdr, tif, cog, write, export, reference, command, ref_command


def measure_geotiff(ctx):
    mid = "geotiff"
    tool = ctx.bench("geotiff_export_tool")
    need_build(ctx, tool)
    d = ctx.work / "io"
    d.mkdir(parents=True, exist_ok=True)
    hdr, tif, cog, write, export, reference, command, ref_command = geotiff_commands(ctx)
    gdal = shutil.which("gdal_translate")
    r = ctx.execute(write, "geotiff_write", timed=False)
    data = {"ok": False, "command": command, "reference_command": ref_command}
    if r["rc"] != 0:
        data["error"] = r["error"]
        ctx.save(mid, data)
        return
    env = dict(os.environ, GDAL_PAM_ENABLED="NO")
    runs, refs, error = [], [], None
    for i in range(ctx.repeats):
        tif.unlink(missing_ok=True)
        x = ctx.execute(export, f"geotiff_export_{i + 1}", env=env)
        if x["rc"] != 0:
            error = x["error"]
            break
        runs.append({"wall_s": x["wall_s"], "cpu_s": x["cpu_s"], "peak_mb": x["peak_mb"]})
    if gdal and error is None:
        for i in range(ctx.repeats):
            cog.unlink(missing_ok=True)
            x = ctx.execute(reference, f"geotiff_reference_{i + 1}", env=env)
            if x["rc"] == 0:
                refs.append({"wall_s": x["wall_s"], "cpu_s": x["cpu_s"], "peak_mb": x["peak_mb"]})
    for p in (hdr, hdr.with_suffix(".raw"), tif, cog):
        p.unlink(missing_ok=True)
    data.update(ok=error is None and bool(runs), error=error, runs=runs, reference=refs,
                reference_error=None if gdal else "not measured: gdal_translate not found")
    ctx.save(mid, data)


# ---------------------------------------------------------------- what each section needs


def section_needs(section, surveys):
    """The measurement ids a section reads, in the order they should run."""
    s = [n for n in PRESETS if n in surveys]
    twenty = [n for n in ("rugged", "flat", "low-relief", "transect-100m") if n in s]
    if section == "simulate":
        return [f"simulate/{n}" for n in s]
    if section == "inspect":
        return ["inspect/rugged"] if "rugged" in s else []
    if section == "frontend":
        return [f"frontend/{n}" for n in twenty]
    if section in ("georef", "refine"):
        return [f"run/{n}/sequential" for n in twenty]
    if section == "scale":
        presets = [f"run/{n}/sequential" for n in s if n != "transect-100m"]
        return presets + [f"run/{n}/{v}" for n in ("short", "short-no-attitude") for v in ("sequential", "joint")] + \
            [f"run/{n}/sequential" for n in ("rugged-black-frames", "rugged-blackout-2s")]
    if section == "surface":
        return [f"run/{n}/{v}" for n in twenty for v in ("sequential", "joint")]
    if section == "joint":
        return [f"run/{n}/{v}" for n in twenty for v in ("sequential", "joint")]
    if section == "variants":
        return [f"run/rugged/{v}" for v in VARIANTS] if "rugged" in s else []
    if section == "compare":
        return ([f"run/rugged/{v}" for v in VARIANTS] + ["compare/rugged"]) if "rugged" in s else []
    if section == "resume":
        return ["run/rugged/sequential", "resume/rugged/sequential"] + \
               [f"restart/rugged/{v}" for v in VARIANTS] if "rugged" in s else []
    if section == "products":
        return (["run/rugged/sequential"] if "rugged" in s else []) + \
               (["products/transect-100m"] if "transect-100m" in s else [])
    if section == "tiny":
        return [f"run/tiny/{v}" for v in VARIANTS] if "tiny" in s else []
    if section == "unlike":
        return [f"run/unlike/{v}" for v in VARIANTS]
    if section == "kernels":
        return list(GBENCH)
    if section == "io":
        return ["envi/bil", "envi/bip", "envi/bsq", "geotiff"]
    raise ValueError(section)


def plan_order(mid):
    """Cheap first: tiny, then the 20 m presets, the kernels and io, transect-100m last."""
    kind, _, rest = mid.partition("/")
    survey = rest.split("/")[0] if kind in ("simulate", "run", "resume", "restart", "inspect", "frontend",
                                             "products", "compare") else None
    survey_rank = {"tiny": 0, "short": 1, "short-no-attitude": 1, "rugged": 1, "flat": 2, "low-relief": 3,
                   "rugged-black-frames": 4, "rugged-blackout-2s": 4}.get(survey, 6 if survey else 5)
    kind_rank = {"simulate": 0, "inspect": 1, "run": 2, "resume": 3, "restart": 3, "compare": 3, "frontend": 4,
                 "products": 5,
                 "gbench": 6, "envi": 7, "geotiff": 8}[kind]
    variant_rank = 0
    if kind == "run":
        variant_rank = {"sequential": 0, "planar": 1, "stacked": 2, "joint": 3}[rest.split("/")[1]]
    return (survey_rank, kind_rank, variant_rank if kind not in ("resume", "restart") else 0, mid)


def run_measurement(ctx, mid):
    if mid in ctx.attempted:
        return
    kind, _, rest = mid.partition("/")
    try:
        if kind == "simulate":
            measure_simulate(ctx, rest)
        elif kind == "run":
            survey, variant = rest.split("/")
            measure_run(ctx, survey, variant)
        elif kind == "resume":
            survey, variant = rest.split("/")
            measure_resume(ctx, survey, variant)
        elif kind == "restart":
            survey, variant = rest.split("/")
            measure_restart(ctx, survey, variant)
        elif kind == "inspect":
            measure_inspect(ctx, rest)
        elif kind == "compare":
            measure_compare(ctx, rest)
        elif kind == "frontend":
            measure_frontend(ctx, rest)
        elif kind == "products":
            measure_products(ctx, rest)
        elif kind == "gbench":
            measure_gbench(ctx, mid)
        elif kind == "envi":
            measure_envi(ctx)
        elif kind == "geotiff":
            measure_geotiff(ctx)
    except Skip as reason:
        if kind != "simulate":
            ctx.save(mid, {"ok": False, "error": str(reason)})
        log(f"{mid}: {reason}")
    except Exception as failure:  # keep going: the page says what failed
        ctx.save(mid, {"ok": False, "error": f"failed: {type(failure).__name__}: {failure}"})
        log(f"{mid}: failed: {failure}")
    ctx.attempted.add(mid)


# ---------------------------------------------------------------- page rows


class Cell:
    """A value cell: text, the number behind it (or None), its measurement."""

    def __init__(self, text, number=None, m=None, command=None):
        self.text, self.number, self.m, self.command = text, number, m, command


def fmt_mm(v):
    return f"{v * 1000:.2f} mm"


def fmt_cm(v):
    return f"{v * 100:.1f} cm"


def fmt_deg(v):
    return f"{v:.3f}°"


def fmt_ms(v):
    return f"{v * 1000:.2f} ms"


def fmt_frac(v):
    return f"{v:.3f}"


def fmt_pct(v):
    return f"{v * 100:.2f} %"


def fmt_s(v):
    if v >= 120:
        return f"{int(v // 60)} min {v % 60:04.1f} s"
    return f"{v:.2f} s" if v < 10 else f"{v:.1f} s"


def fmt_mb(v):
    return f"{v / 1024:.2f} GB" if v >= 1024 else f"{v:.0f} MB"


def spread(values, fmt):
    values = [v for v in values if v is not None]
    if len(values) < 2:
        return f"{fmt(values[0])} (1 run)" if values else "not measured"
    return f"{fmt(median(values))} (median of {len(values)}, {fmt(min(values))}–{fmt(max(values))})"


class Page:
    def __init__(self, ctx, surveys, only):
        self.ctx, self.surveys, self.only = ctx, surveys, only

    def missing(self, mid):
        kind, _, rest = mid.partition("/")
        survey = rest.split("/")[0] if kind in ("simulate", "run", "resume", "inspect", "frontend",
                                                "products") else None
        if self.ctx.args.from_work:
            return "not measured: no result in WORK (--from-work measures nothing)"
        if survey and survey in PRESETS and survey not in self.surveys:
            return f"not measured: {survey} not among --surveys"
        if kind == "simulate" and (self.ctx.survey(rest) / "survey.yaml").exists():
            return f"not measured: {self.ctx.path(self.ctx.survey(rest))} existed (delete it to time the simulation)"
        return "not measured: its section was not selected (--only)"

    def get(self, mid):
        return self.ctx.results.get(mid)

    def measured(self, mid):
        """(measurement, None) or (None, reason)."""
        m = self.get(mid)
        if m is None:
            return None, self.missing(mid)
        if not m.get("ok"):
            return None, m.get("error") or "failed"
        return m, None

    def metric(self, survey, variant, key, fmt):
        mid = f"run/{survey}/{variant}"
        m, why = self.measured(mid)
        cmd = self.run_command(survey, variant, m)
        if m is None:
            return Cell(why, m=self.get(mid), command=cmd)
        if not m.get("evaluate_ok", False):
            error = m.get("evaluate_error") or "failed"
            return Cell("failed: hsmap evaluate: " + error[len("failed: "):] if error.startswith("failed: ")
                        else error, m=m, command=cmd)
        metrics = m.get("metrics", {})
        if key not in metrics:
            return Cell(f"not measured: metrics.json has no `{key}` (this hsmap does not compute it)", m=m,
                        command=cmd)
        value = metrics[key]
        if value is None:
            reason = m.get("null_reasons", {}).get(key)
            return Cell("null" + (f": {reason}" if reason else ""), m=m, command=cmd)
        return Cell(fmt(value), value, m, cmd)

    def run_command(self, survey, variant, m=None):
        ctx = self.ctx
        run = (m or {}).get("command") or ctx.show(run_argv(ctx, survey, variant))
        ev = (m or {}).get("evaluate_command") or ctx.show(evaluate_argv(ctx, survey, variant))
        return f"{run} && {ev}"

    def run_time(self, survey, variant, what="wall"):
        """Whole-run wall time or peak memory (/usr/bin/time -v), or a stage's time (run.yaml)."""
        mid = f"run/{survey}/{variant}"
        m, why = self.measured(mid)
        ctx = self.ctx
        cmd = "/usr/bin/time -v " + ((m or {}).get("command") or ctx.show(run_argv(ctx, survey, variant)))
        if m is None:
            return Cell(why, m=self.get(mid), command=cmd)
        if what == "wall":
            v = m["wall_s"][0]
            return Cell(fmt_s(v) + " (1 run)", v, m, cmd)
        if what == "peak":
            v = m["peak_mb"][0]
            return Cell(fmt_mb(v), v, m, cmd)
        stage = m.get("stages", {}).get(what)
        if stage is None:
            return Cell(f"not measured: RUN/run.yaml has no stage {what}", m=m, command=cmd)
        return Cell(fmt_s(stage["time_s"]) + " (1 run; run.yaml)", stage["time_s"], m, cmd)


class Goal:
    def __init__(self, text, check=None):
        self.text, self.check = text, check


def at_most(limit, text):
    return Goal(text, lambda v, page: v <= limit)


def at_least(limit, text):
    return Goal(text, lambda v, page: v >= limit)


NO_GOAL = Goal("—")
IDENTICAL = Goal("byte-identical", lambda v, page: v == 1.0)


def render_row(figure, goal, cell, page):
    value = cell.text
    if cell.number is not None and goal.check is not None:
        try:
            met = goal.check(cell.number, page)
        except Exception:  # a goal that needs another figure which is missing
            met = None
        if met is True:
            value += " — met"
        elif met is False:
            value += " — **not met**"
    commit = (cell.m or {}).get("commit", "—") if cell.m else "—"
    date = (cell.m or {}).get("date_utc", "")[:10] if cell.m else ""
    commit_text = f"{commit} ({date})" if date else commit
    command = code(cell.command) if cell.command else "—"
    return f"| {md(figure)} | {md(goal.text)} | {md(value)} | {command} | {commit_text} |"


TABLE_HEAD = ["| figure | goal | value | command | commit |", "|---|---|---|---|---|"]


def metric_value(page, survey, variant, key):
    m = page.get(f"run/{survey}/{variant}")
    if not m or not m.get("ok"):
        return None
    return (m.get("metrics") or {}).get(key)


def sections(page):
    """{name: (title, intro lines, rows)}; rows are (figure, Goal, Cell)."""
    ctx = page.ctx
    out = {}
    twenty = ["rugged", "flat", "low-relief", "transect-100m"]

    # simulate
    rows = []
    for n in PRESETS:
        mid = f"simulate/{n}"
        m, why = page.measured(mid)
        cmd = (page.get(mid) or {}).get("command") or "/usr/bin/time -v " + ctx.show(simulate_argv(ctx, n))
        goal = at_most(300, "< 5 min on 2 cores") if n == "rugged" else NO_GOAL
        if m is None:
            rows.append((f"{n}: simulation wall time", goal, Cell(why, m=page.get(mid), command=cmd)))
            continue
        rows.append((f"{n}: simulation wall time", goal, Cell(fmt_s(m["wall_s"][0]) + " (1 run)", m["wall_s"][0], m, cmd)))
        rows.append((f"{n}: simulation peak memory", NO_GOAL, Cell(fmt_mb(m["peak_mb"][0]), m["peak_mb"][0], m, cmd)))
    out["simulate"] = ("Simulator (`hsmap simulate`)",
                       ["The preset surveys every other section runs on, written into WORK/surveys/NAME."], rows)

    # inspect
    rows = []
    mid = "inspect/rugged"
    m, why = page.measured(mid)
    cmd = (page.get(mid) or {}).get("command") or "/usr/bin/time -v " + ctx.show([ctx.hsmap(), "inspect", ctx.survey("rugged")])
    if m is None:
        rows.append(("rugged: `hsmap inspect` wall time", at_most(5, "< 5 s"), Cell(why, m=page.get(mid), command=cmd)))
    else:
        rows.append(("rugged: `hsmap inspect` wall time", at_most(5, "< 5 s"),
                     Cell(spread(m["wall_s"], fmt_s), median(m["wall_s"]), m, cmd)))
        rows.append(("rugged: `hsmap inspect` peak memory", NO_GOAL, Cell(fmt_mb(max(m["peak_mb"])), max(m["peak_mb"]), m, cmd)))
    out["inspect"] = ("Survey validation (`hsmap inspect`)",
                      ["Every frame's header, the tables, the cube's header and size, the INS track; page cache warm."],
                      rows)

    # frontend
    rows = []
    for n in twenty:
        mid = f"frontend/{n}"
        m, why = page.measured(mid)
        cmd = (page.get(mid) or {}).get("command") or "/usr/bin/time -v " + ctx.show([ctx.bench("frontend_measure_tool"), ctx.survey(n)])
        if m is None:
            rows.append((f"{n}: front-end", NO_GOAL, Cell(why, m=page.get(mid), command=cmd)))
            continue
        runs = m["runs"]
        first = runs[0]
        posed_goal = Goal(f"all {first['frames']}", lambda v, p, f=first["frames"]: v == f)
        rows.append((f"{n}: frames posed", posed_goal, Cell(f"{first['posed']} of {first['frames']}", first["posed"], m, cmd)))
        pct = first.get("percent_of_path")
        rows.append((f"{n}: aligned frame RMS, % of the path", at_most(0.5, "≤ 0.5 %"),
                     Cell(f"{pct:.3f} % ({first['aligned_rms_m'] * 1000:.1f} mm)" if pct is not None else
                          "not measured: the tool printed no aligned error", pct, m, cmd)))
        rows.append((f"{n}: frames/s, tracking alone", at_least(50, "≥ 50"),
                     Cell(spread([r["tracking_fps"] for r in runs], lambda v: f"{v:.1f}"),
                          median([r["tracking_fps"] for r in runs]), m, cmd)))
        rows.append((f"{n}: frames/s with PNG decoding", at_least(25, "≥ 25"),
                     Cell(spread([r["fps"] for r in runs], lambda v: f"{v:.1f}"), median([r["fps"] for r in runs]), m, cmd)))
        peak = max(r["peak_mb"] for r in runs)
        rows.append((f"{n}: peak memory", at_most(1024, "< 1 GB") if n == "transect-100m" else NO_GOAL,
                     Cell(fmt_mb(peak), peak, m, cmd)))
    out["frontend"] = ("Visual front-end",
                       ["`frontend_measure_tool` runs the front-end alone (as `hsmap run --until frontend`) and aligns "
                        "the posed frames to `truth/rgb_poses.csv` with one Sim(3)."], rows)

    # georef
    rows = []
    for n in twenty:
        floor = metric_value(page, n, "sequential", "ins_floor_rgb_ate_m")
        goal = Goal("≤ INS floor + 5 mm" + (f" ({fmt_cm(floor)} + 5 mm)" if floor is not None else ""),
                    (lambda v, p, f=floor: v <= f + 0.005) if floor is not None else None)
        rows.append((f"{n}: `rgb_ate_m` (sequential)", goal, page.metric(n, "sequential", "rgb_ate_m", fmt_cm)))
        rows.append((f"{n}: `rgb_ate_aligned_m` (sequential)", at_most(0.01, "≤ 1 cm"),
                     page.metric(n, "sequential", "rgb_ate_aligned_m", fmt_mm)))
        limit = {"rugged": (20, "< 20 s"), "transect-100m": (120, "< 2 min")}.get(n)
        rows.append((f"{n}: georef stage time", at_most(*limit) if limit else NO_GOAL, page.run_time(n, "sequential", "georef")))
    out["georef"] = ("Geo-referencing (`georef` stage)",
                     ["From the `sequential` runs; **INS floor** is `ins_floor_rgb_ate_m` (docs/EVALUATE.md): the "
                      "true trajectory placed by the INS fixes alone."], rows)

    # scale: the map's size against what the INS allows, and tracking losses
    rows = []
    for n in ["tiny", "rugged", "flat", "low-relief", "short", "short-no-attitude"]:
        floor = metric_value(page, n, "sequential", "ins_floor_scale_error")
        goal = Goal("≤ 1.5 × INS floor" + (f" ({fmt_pct(1.5 * floor)})" if floor is not None else ""),
                    (lambda v, p, f=floor: v <= 1.5 * f) if floor is not None else None)
        rows.append((f"{n}: `rgb_scale_error` / INS floor (sequential)", goal,
                     combine(page.metric(n, "sequential", "rgb_scale_error", fmt_pct),
                             page.metric(n, "sequential", "ins_floor_scale_error", fmt_pct))))
        floor = metric_value(page, n, "sequential", "ins_floor_rgb_ate_m")
        goal = Goal("≤ 1.1 × INS floor" + (f" ({fmt_cm(1.1 * floor)})" if floor is not None else ""),
                    (lambda v, p, f=floor: v <= 1.1 * f) if floor is not None else None)
        rows.append((f"{n}: `rgb_ate_m` / INS floor (sequential)", goal,
                     combine(page.metric(n, "sequential", "rgb_ate_m", fmt_cm),
                             page.metric(n, "sequential", "ins_floor_rgb_ate_m", fmt_cm))))
    for n in ["short", "short-no-attitude"]:
        rows.append((f"{n}: `extrinsic_translation_error_m` (joint)", at_most(0.01, "≤ 1 cm"),
                     page.metric(n, "joint", "extrinsic_translation_error_m", fmt_mm)))
        rows.append((f"{n}: `ortho_registration_rmse_m` (sequential)", NO_GOAL,
                     page.metric(n, "sequential", "ortho_registration_rmse_m", fmt_mm)))
    for n in ["rugged-black-frames", "rugged-blackout-2s"]:
        for key, fmt in (("mesh_completeness", fmt_frac), ("mesh_accuracy_m", fmt_mm),
                         ("ortho_registration_rmse_m", fmt_mm)):
            reference = metric_value(page, "rugged", "sequential", key)
            if key == "mesh_completeness":
                goal = Goal("≥ 0.8 × rugged's" + (f" ({fmt(0.8 * reference)})" if reference is not None else ""),
                            (lambda v, p, r=reference: v >= 0.8 * r) if reference is not None else None)
            else:
                goal = Goal("≤ 1.2 × rugged's" + (f" ({fmt(1.2 * reference)})" if reference is not None else ""),
                            (lambda v, p, r=reference: v <= 1.2 * r) if reference is not None else None)
            rows.append((f"{n}: `{key}` (sequential)", goal, page.metric(n, "sequential", key, fmt)))
    out["scale"] = ("The map's scale, and tracking losses (`frontend` and `georef` stages)",
                    ["`rgb_scale_error` against `ins_floor_scale_error` (docs/EVALUATE.md: the true trajectory "
                     "fitted to the same INS fixes by the same estimator), from the `sequential` runs. `short` and "
                     "`short-no-attitude`: 4.4 m of track, 9-12 INS fixes "
                     "(`hsmap simulate --config benchmarks/short_survey.yaml`, `short_survey_no_attitude.yaml`). "
                     "`rugged-black-frames` (8 black frames) and `rugged-blackout-2s` (2 s of black frames): "
                     "`rugged` with a tracking loss (`benchmarks/rugged_black_frames.yaml`, "
                     "`rugged_blackout_2s.yaml`), against `rugged` itself. Three seeds of each short survey, "
                     "with the stated 1-sigma of the scale: docs/GEOREF.md."], rows)

    # surface
    rows = []
    acc_goal = {"rugged": (0.005, "≤ 5 mm"), "flat": (0.003, "≤ 3 mm"), "low-relief": (0.003, "≤ 3 mm")}
    comp_goal = {"rugged": (0.90, "≥ 0.90"), "flat": (0.97, "≥ 0.97"), "low-relief": (0.97, "≥ 0.97")}
    for n in twenty:
        for v in ("sequential", "joint"):
            g = acc_goal.get(n)
            rows.append((f"{n}: `mesh_accuracy_m` ({v})", at_most(*g) if g else NO_GOAL,
                         page.metric(n, v, "mesh_accuracy_m", fmt_mm)))
        g = comp_goal.get(n)
        rows.append((f"{n}: `mesh_completeness` (sequential)", at_least(*g) if g else NO_GOAL,
                     page.metric(n, "sequential", "mesh_completeness", fmt_frac)))
        limit = {"rugged": (60, "< 60 s"), "transect-100m": (300, "< 5 min")}.get(n)
        rows.append((f"{n}: surface stage time (sequential)", at_most(*limit) if limit else NO_GOAL,
                     page.run_time(n, "sequential", "surface")))
    out["surface"] = ("Surface (`surface` stage, dense)",
                      ["The mesh against `truth/scene.ply` after the frames' view Sim(3) (docs/EVALUATE.md)."], rows)

    # refine (sequential)
    rows = []
    for n in twenty:
        g = (0.0048, "≤ 4.8 mm") if n == "rugged" else (0.010, "≤ 10 mm")
        rows.append((f"{n}: `ortho_registration_rmse_m` (sequential)", at_most(*g),
                     page.metric(n, "sequential", "ortho_registration_rmse_m", fmt_mm)))
        rows.append((f"{n}: `ortho_coverage` (sequential)", at_least(0.95, "≥ 0.95"),
                     page.metric(n, "sequential", "ortho_coverage", fmt_frac)))
        rows.append((f"{n}: `T_C_U` rotation / translation error after refine", NO_GOAL,
                     combine(page.metric(n, "sequential", "extrinsic_rotation_error_deg", fmt_deg),
                             page.metric(n, "sequential", "extrinsic_translation_error_m", fmt_mm))))
        rows.append((f"{n}: refine stage time", NO_GOAL, page.run_time(n, "sequential", "refine")))
    out["refine"] = ("Sequential refinement (`refine` stage)",
                     ["`T_C_U` refined from the RGB and hyperspectral ortho-images (2 rounds); `d` stays at "
                      "survey.yaml's guess (15 ms off)."], rows)

    # joint
    rows = []
    for n in twenty:
        main = n == "rugged"
        rows.append((f"{n}: `extrinsic_rotation_error_deg` (joint)", at_most(0.1, "≤ 0.1°") if main else NO_GOAL,
                     page.metric(n, "joint", "extrinsic_rotation_error_deg", fmt_deg)))
        rows.append((f"{n}: `extrinsic_translation_error_m` (joint)", at_most(0.01, "≤ 1 cm") if main else NO_GOAL,
                     page.metric(n, "joint", "extrinsic_translation_error_m", fmt_mm)))
        rows.append((f"{n}: `time_offset_error_s` (joint)", at_most(0.002, "≤ 2 ms") if main else NO_GOAL,
                     page.metric(n, "joint", "time_offset_error_s", fmt_ms)))
        seq = metric_value(page, n, "sequential", "ortho_registration_rmse_m")
        if main:
            g = at_most(0.0045, "≤ 4.5 mm")
        else:
            g = Goal("< sequential's" + (f" ({fmt_mm(seq)})" if seq is not None else ""),
                     (lambda v, p, s=seq: v < s) if seq is not None else None)
        rows.append((f"{n}: `ortho_registration_rmse_m` (joint)", g,
                     page.metric(n, "joint", "ortho_registration_rmse_m", fmt_mm)))
        rows.append((f"{n}: `rgb_ate_aligned_m` (joint)", NO_GOAL, page.metric(n, "joint", "rgb_ate_aligned_m", fmt_mm)))
        rows.append((f"{n}: whole joint run, wall time", at_most(600, "≤ 10 min") if main else NO_GOAL,
                     page.run_time(n, "joint", "wall")))
        rows.append((f"{n}: whole joint run, peak memory", NO_GOAL, page.run_time(n, "joint", "peak")))
    out["joint"] = ("Joint (`hsmap run --variant joint`)",
                    ["One spline trajectory, `T_C_U` and `d` estimated with cross-modal tie points (3 rounds), from "
                     "the simulator's guess (2°, 5 cm, 15 ms off)."], rows)

    # variants
    rows = []
    joint_px = metric_value(page, "rugged", "joint", "ortho_pixel_error_m")
    seq_px = metric_value(page, "rugged", "sequential", "ortho_pixel_error_m")
    goals = {
        "stacked": NO_GOAL,
        "planar": Goal("≥ 10 × joint's", (lambda v, p, j=joint_px: v >= 10 * j) if joint_px else None),
        "sequential": NO_GOAL,
        "joint": Goal("≤ 3.5 mm and < sequential's",
                      lambda v, p, s=seq_px: (v <= 0.0035 and v < s) if s is not None
                      else (None if v <= 0.0035 else False)),
    }
    for v in VARIANTS:
        rows.append((f"rugged: `ortho_pixel_error_m` ({v})", goals[v], page.metric("rugged", v, "ortho_pixel_error_m", fmt_mm)))
    for v in VARIANTS:
        wall, peak = page.run_time("rugged", v, "wall"), page.run_time("rugged", v, "peak")
        if wall.number is not None:
            wall.text = f"{wall.text.replace(' (1 run)', '')}, peak {peak.text}"
        rows.append((f"rugged: whole {v} run, wall time and peak memory", NO_GOAL, wall))
    out["variants"] = ("Variants side by side (rugged)",
                       ["`ortho_pixel_error_m`: where each ortho pixel's scan line and sample truly see the seabed, "
                        "against the pixel (docs/EVALUATE.md); defined for every variant with a map position."], rows)

    # compare
    rows = []
    mid = "compare/rugged"
    m, why = page.measured(mid)
    cmd = (page.get(mid) or {}).get("command") or "/usr/bin/time -v " + ctx.show(compare_argv(ctx, "rugged"))
    separate = [page.get(f"run/rugged/{v}") for v in VARIANTS]
    target = None
    if all(r and r.get("ok") for r in separate):
        fronts = [r.get("stages", {}).get("frontend", {}).get("time_s") for r in separate
                  if r.get("stages", {}).get("frontend")]
        if fronts:
            target = sum(r["wall_s"][0] for r in separate) - 3 * median(fronts)
    goal = Goal("≤ the four runs minus three front-ends" + (f" ({fmt_s(target)})" if target else ""),
                (lambda v, p, t=target: v <= t) if target else None)
    if m is None:
        rows.append(("rugged: `hsmap compare`, all four variants, wall time", goal, Cell(why, m=page.get(mid), command=cmd)))
    else:
        parts = ", ".join(f"{k} {fmt_s(v)}" for k, v in m.get("variants", {}).items())
        rows.append(("rugged: `hsmap compare`, all four variants, wall time", goal,
                     Cell(fmt_s(m["wall_s"][0]) + f" (1 run; {parts})", m["wall_s"][0], m, cmd)))
        rows.append(("rugged: `hsmap compare` peak memory", NO_GOAL, Cell(fmt_mb(m["peak_mb"][0]), m["peak_mb"][0], m, cmd)))
    out["compare"] = ("One command for all variants (`hsmap compare`)",
                      ["The four variants on rugged, each evaluated, with the stages they share run once (docs/COMPARE.md); "
                       "the goal is the sum of the four `run/rugged/*` runs of this page minus three front-ends "
                       "(their `frontend` stage, median)."], rows)

    # resume
    rows = []
    mid = "resume/rugged/sequential"
    m, why = page.measured(mid)
    cmd = (page.get(mid) or {}).get("command") or "/usr/bin/time -v " + ctx.show(run_argv(ctx, "rugged", "sequential"))
    if m is None:
        rows.append(("rugged: the same `hsmap run` again on a finished run", at_most(5, "< 5 s"),
                     Cell(why, m=page.get(mid), command=cmd)))
    else:
        rows.append(("rugged: the same `hsmap run` again on a finished run", at_most(5, "< 5 s"),
                     Cell(spread(m["wall_s"], fmt_s) + ", every stage skipped", median(m["wall_s"]), m, cmd)))
    for variant in ("sequential", "joint", "planar", "stacked"):
        mid = f"restart/rugged/{variant}"
        m, why = page.measured(mid)
        cmd = (page.get(mid) or {}).get("command") or f"benchmarks/resume_benchmark.sh SURVEY {variant} -- build"
        if m is None:
            rows.append((f"rugged {variant}: `--from X` (each stage) on a finished run, against the full run's products",
                         IDENTICAL, Cell(why, m=page.get(mid), command=cmd)))
            continue
        order = ["frontend", "georef", "surface", "refine", "joint", "products"]
        for stage, result in sorted(m["stages"].items(), key=lambda item: order.index(item[0])
                                    if item[0] in order else len(order)):
            identical = 1.0 if result["result"].startswith("products byte-identical") else 0.0
            rows.append((f"rugged {variant}: `--from {stage}` on a finished run (`--threads 1`)", IDENTICAL,
                         Cell(f"{result['result']}; {result['wall_s']:.0f} s", identical, m, cmd)))
    out["resume"] = ("Resuming and restarting (docs/RUN.md)",
                     ["A second `hsmap run` with the same arguments finds every stage up to date and skips it; "
                      "`--from X` redoes X and the stages after it from the files of those before, and gives "
                      "the full run's products byte for byte with `--threads 1`."], rows)

    # products
    rows = [("rugged: products stage time (sequential, no GeoTIFF)", NO_GOAL, page.run_time("rugged", "sequential", "products"))]
    mid = "products/transect-100m"
    m, why = page.measured(mid)
    cmd = (page.get(mid) or {}).get("command") or products_command(ctx, "transect-100m")
    if m is None:
        rows.append(("transect-100m: products scan lines/s", at_least(600, "≥ 600"), Cell(why, m=page.get(mid), command=cmd)))
    else:
        reps = m["repeats"]
        rows.append(("transect-100m: products scan lines/s (stage time, run.yaml)", at_least(600, "≥ 600"),
                     Cell(spread([r["lines_per_s"] for r in reps], lambda v: f"{v:.0f}") + f" of {m['lines']} lines",
                          median([r["lines_per_s"] for r in reps]), m, cmd)))
        peak = max(r["peak_mb"] for r in reps)
        rows.append(("transect-100m: products peak memory", at_most(2048, "< 2 GB"), Cell(fmt_mb(peak), peak, m, cmd)))
        rows.append(("transect-100m: products stage / `cat cube.raw` from storage", at_most(3, "≤ 3"),
                     Cell(spread([r["stage_over_cat"] for r in reps], lambda v: f"{v:.2f}")
                          + f" (cat {fmt_s(median([r['cat_s'] for r in reps]))} for {m['cube_gb']:.1f} GB)",
                          median([r["stage_over_cat"] for r in reps]), m, cmd)))
    out["products"] = ("Products (`products` stage)",
                       ["The ray casting and the hyperspectral ortho-image (5 mm pixels) with `--no-geotiff "
                        "--no-points`; on transect-100m timed alone (`--from products`) after the cube is dropped "
                        "from the page cache and read once by `cat`."], rows)

    # tiny
    rows = []
    for v in VARIANTS:
        rows.append((f"tiny: whole {v} run, wall time", NO_GOAL, page.run_time("tiny", v, "wall")))
    for v in ("planar", "sequential", "joint"):
        rows.append((f"tiny: `ortho_pixel_error_m` ({v})", NO_GOAL, page.metric("tiny", v, "ortho_pixel_error_m", fmt_mm)))
    rows.append(("tiny: `rgb_ate_aligned_m` (joint)", NO_GOAL, page.metric("tiny", "joint", "rgb_ate_aligned_m", fmt_mm)))
    rows.append(("tiny: `ortho_registration_rmse_m` (sequential)", NO_GOAL,
                 page.metric("tiny", "sequential", "ortho_registration_rmse_m", fmt_mm)))
    out["tiny"] = ("The `tiny` preset (every variant end to end)",
                   ["A 1.2 m survey for quick checks; the tests run on it."], rows)

    # unlike
    rows = []
    for v in VARIANTS:
        rows.append((f"unlike: whole {v} run, wall time", NO_GOAL, page.run_time("unlike", v, "wall")))
    for v in ("planar", "sequential", "joint"):
        rows.append((f"unlike: `ortho_pixel_error_m` ({v})", NO_GOAL,
                     page.metric("unlike", v, "ortho_pixel_error_m", fmt_mm)))
    for v in ("sequential", "joint"):
        rows.append((f"unlike: `ortho_registration_rmse_m` ({v})", at_most(0.010, "≤ 10 mm"),
                     page.metric("unlike", v, "ortho_registration_rmse_m", fmt_mm)))
        rows.append((f"unlike: `mesh_accuracy_m` ({v})", at_most(0.005, "≤ 5 mm"),
                     page.metric("unlike", v, "mesh_accuracy_m", fmt_mm)))
    rows.append(("unlike: `extrinsic_rotation_error_deg` (joint)", NO_GOAL,
                 page.metric("unlike", "joint", "extrinsic_rotation_error_deg", lambda x: f"{x:.3f}°")))
    rows.append(("unlike: `time_offset_error_s` (joint)", NO_GOAL,
                 page.metric("unlike", "joint", "time_offset_error_s", lambda x: f"{x * 1000:.2f} ms")))
    out["unlike"] = ("A survey unlike the presets",
                     [f"`hsmap simulate --config {UNLIKE_CONFIG}` (800 × 600 camera with strong distortion, "
                      "480 samples × 40 bands), then the INS's attitude columns cut and the cube rewritten "
                      "big-endian BIP (`scripts/rewrite_cube.py SURVEY --interleave bip --byte-order 1`), as "
                      "surveys written by other programs come."], rows)

    # kernels
    rows = []

    def gb(mid, name, counter, figure, goal, fmt):
        m, why = page.measured(mid)
        cmd = (page.get(mid) or {}).get("command") or ctx.show(gbench_argv(ctx, mid)[:-1])
        if m is None:
            return (figure, goal, Cell(why, m=page.get(mid), command=cmd))
        # Google Benchmark names a run by its arguments and settings
        # ("BM_X/linear_solver:0/iterations:1/real_time"): the first whose
        # name is `name` or starts with it and a "/".
        benchmarks = m.get("benchmarks", {})
        b = benchmarks.get(name) or next(
            (v for k, v in sorted(benchmarks.items()) if k.startswith(name + "/")), None)
        if b is None or (counter not in b):
            return (figure, goal, Cell(f"not measured: no {name} {counter} in the JSON output", m=m, command=cmd))
        reps = m.get("context", {}).get("repetitions") or ctx.repeats
        return (figure, goal, Cell(fmt(b[counter]) + f" (median of {reps})", b[counter], m, cmd))

    rows.append(gb("gbench/engine_ba", "BM_KeyframeBundleAdjustment/linear_solver:0", "solve_s",
                   "keyframe BA, 1,000 keyframes, 50,000 landmarks: solve", at_most(30, "< 30 s"), fmt_s))
    rows.append(gb("gbench/engine_spline", "BM_SplineJointCalibration/linear_solver:0", "solve_s",
                   "spline + push-broom calibration (5,000 control points): solve", NO_GOAL, fmt_s))
    rows.append(gb("gbench/raycast", "BM_CameraFrameBatch/2", "items_per_second",
                   "ray casting, camera rays batched per row, 2 threads", NO_GOAL, lambda v: f"{v / 1e6:.1f} Mray/s"))
    rows.append(gb("gbench/raycast", "BM_CameraFrameBatch/1", "items_per_second",
                   "ray casting, camera rays batched per row, 1 thread", NO_GOAL, lambda v: f"{v / 1e6:.1f} Mray/s"))
    rows.append(gb("gbench/raycast", "BM_CameraFrameSingleRays/2", "items_per_second",
                   "ray casting, single camera rays, 2 threads", NO_GOAL, lambda v: f"{v / 1e6:.1f} Mray/s"))
    rows.append(gb("gbench/raycast", "BM_SceneBuild/2", "real_time",
                   "Embree scene build, 776,802 triangles, 2 threads", NO_GOAL, lambda v: f"{v:.0f} ms"))
    out["kernels"] = ("Kernels (Google Benchmark, `BUILD/benchmarks/`)",
                      ["The factor-graph engine on survey-sized synthetic problems (docs/ENGINE.md) and the "
                       "Embree ray caster; medians of repetitions."], rows)

    # io
    rows = []
    for il in ("bil", "bip", "bsq"):
        mid = f"envi/{il}"
        m, why = page.measured(mid)
        cmd = (page.get(mid) or {}).get("command") or envi_commands(ctx, il)[3]
        if m is None:
            rows.append((f"ENVI {il} streaming read (buffered) / `cat`", at_most(2, "≤ 2"), Cell(why, m=page.get(mid), command=cmd)))
            continue
        ratio = median(m["read_s"]) / median(m["cat_s"]) if median(m["cat_s"]) else None
        rows.append((f"ENVI {il} streaming read (buffered) / `cat`, 2.1 GB page-cached", at_most(2, "≤ 2"),
                     Cell(f"{ratio:.2f} (medians of {len(m['read_s'])}: {fmt_s(median(m['read_s']))} / "
                          f"{fmt_s(median(m['cat_s']))})", ratio, m, cmd)))
        rows.append((f"ENVI {il} reader peak memory", at_most(200, "< 200 MB"), Cell(fmt_mb(max(m["peak_mb"])), max(m["peak_mb"]), m, cmd)))
    m, why = page.measured("geotiff")
    cmd = (page.get("geotiff") or {}).get("command") or geotiff_commands(ctx)[6]
    if m is None:
        rows.append(("GeoTIFF export of a 2 GB ortho, peak memory", at_most(500, "< 500 MB"), Cell(why, m=page.get("geotiff"), command=cmd)))
    else:
        peak = max(r["peak_mb"] for r in m["runs"])
        rows.append(("GeoTIFF export of a 2 GB ortho (600 × 4000 × 211), peak memory", at_most(500, "< 500 MB"),
                     Cell(fmt_mb(peak), peak, m, cmd)))
        cpu = median([r["cpu_s"] for r in m["runs"]])
        if m.get("reference"):
            ref = median([r["cpu_s"] for r in m["reference"]])
            rows.append(("GeoTIFF export CPU time / `gdal_translate -of COG`'s", at_most(1, "≤ 1"),
                         Cell(f"{cpu / ref:.2f} ({fmt_s(cpu)} / {fmt_s(ref)}, medians)", cpu / ref, m,
                              m.get("reference_command"))))
        else:
            rows.append(("GeoTIFF export CPU time / `gdal_translate -of COG`'s", at_most(1, "≤ 1"),
                         Cell(m.get("reference_error") or "not measured: the reference failed", m=m,
                              command=m.get("reference_command"))))
    out["io"] = ("Input and output (ENVI reader, GeoTIFF export)",
                 ["Synthetic files written by `envi_stream_tool` and `geotiff_export_tool` into WORK/io "
                  "and deleted after."], rows)
    return out


def combine(a, b):
    if a.number is None:
        return a
    if b.number is None:
        return Cell(a.text + " / " + b.text, None, a.m, a.command)
    return Cell(a.text + " / " + b.text, a.number, a.m, a.command)


def write_page(ctx, surveys, only, argv_text, path):
    page = Page(ctx, surveys, only)
    head, dirty = ctx.commit, ctx.dirty
    mach = machine()
    lines = ["# Benchmarks", "",
             "The current figures, one table per stage: each value with its goal, the command that measured it "
             "and the commit it was measured at (`+dirty`: uncommitted changes in the tree). The history, and the "
             "analyses behind earlier figures, are in git (`git log -p docs/BENCHMARKS.md`). Fuzzing figures: "
             "[FUZZING.md](FUZZING.md#results).", "",
             "Regenerate (one measurement at a time; everything takes hours, `transect-100m` writes 13 GB):", "",
             "```",
             "benchmarks/benchmarks_page.py --build build --work /tmp/hsmap-bench                 # every section",
             "benchmarks/benchmarks_page.py --build build --work /tmp/hsmap-bench --only joint    # one section; the others keep WORK's values",
             "benchmarks/benchmarks_page.py --work /tmp/hsmap-bench --from-work                    # the page from the stored results",
             "```", "",
             f"This page: `{argv_text}`.", "",
             f"Machine: {mach['nproc']} cores ({mach['cpu']}), {mach['memory_gb']:.0f} GB, kernel {mach['kernel']}. "
             f"Page written at commit {head}{' with uncommitted changes (+dirty)' if dirty else ''}, "
             f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC. "
             "Surveys: `hsmap simulate --preset NAME --out WORK/surveys/NAME`; run folders: WORK/runs/SURVEY-VARIANT; "
             "raw results (JSON): WORK/results/. Speed figures are medians of repeats "
             f"(`--repeats`, {ctx.repeats} here); whole runs are timed once. A value that could not be produced says "
             "why; `null` is a metric hsmap evaluate could not measure, with its reason.", ""]
    for name, (title, intro, rows) in sections(page).items():
        lines += [f"## {title}", ""] + intro + [f"Section `{name}`.", ""] + TABLE_HEAD
        for figure, goal, cell in rows:
            lines.append(render_row(figure, goal, cell, page))
        lines.append("")
    text = "\n".join(lines).rstrip() + "\n"
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(str(path) + ".partial")
    tmp.write_text(text)
    tmp.replace(path)
    return text


# ---------------------------------------------------------------- main


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog="sections: " + " ".join(SECTIONS) + "\npresets: " + " ".join(PRESETS))
    parser.add_argument("--build", help="build folder holding tools/hsmap and benchmarks/ (not needed with --from-work)")
    parser.add_argument("--work", required=True, help="work folder: surveys/, runs/, results/, logs/")
    parser.add_argument("--surveys", nargs="+", choices=PRESETS, default=PRESETS, metavar="NAME")
    parser.add_argument("--only", nargs="+", choices=SECTIONS, metavar="SECTION")
    parser.add_argument("--from-work", action="store_true", help="measure nothing; the page from WORK/results/")
    parser.add_argument("--repeats", type=int, default=3, help="repeats of each speed figure (median quoted)")
    parser.add_argument("--threads", type=int, help="passed as --threads N to every hsmap run")
    parser.add_argument("--display-build", help="the build folder as the page's commands write it")
    parser.add_argument("--page", default=str(REPO / "docs" / "BENCHMARKS.md"), help="the page to write")
    args = parser.parse_args()
    if not args.from_work and not args.build:
        parser.error("--build is required unless --from-work")
    if args.build and not args.from_work and not (Path(args.build) / "tools" / "hsmap").exists():
        log(f"warning: {args.build}/tools/hsmap not found: the hsmap figures will say so")

    ctx = Ctx(args)
    ctx.work.mkdir(parents=True, exist_ok=True)
    ctx.load_results()
    started = time.monotonic()
    selected = args.only or SECTIONS
    if not args.from_work:
        needed = []
        for section in selected:
            for mid in section_needs(section, args.surveys):
                if mid not in needed:
                    needed.append(mid)
        needed.sort(key=plan_order)
        log(f"{len(needed)} measurements: {' '.join(needed)}")
        for mid in needed:
            run_measurement(ctx, mid)

    shown = ["benchmarks/benchmarks_page.py"]
    if args.build:
        shown += ["--build", ctx.display_build]
    shown += ["--work", ctx.path(ctx.work)]
    if args.surveys != PRESETS:
        shown += ["--surveys", *args.surveys]
    if args.only:
        shown += ["--only", *args.only]
    if args.repeats != 3:
        shown += ["--repeats", str(args.repeats)]
    if args.threads is not None:
        shown += ["--threads", str(args.threads)]
    if args.from_work:
        shown.append("--from-work")
    text = write_page(ctx, args.surveys, args.only, " ".join(shown), args.page)

    # Summary
    counts = {"measured": 0, "not measured": 0, "failed": 0, "null": 0}
    for line in text.splitlines():
        if not line.startswith("| ") or line.startswith("| figure") or line.startswith("|---"):
            continue
        value = line.split(" | ")[2]
        if value.startswith("not measured"):
            counts["not measured"] += 1
        elif value.startswith("failed"):
            counts["failed"] += 1
        elif value.startswith("null"):
            counts["null"] += 1
        else:
            counts["measured"] += 1
    log(f"wrote {args.page}: {len(text.splitlines())} lines; figures: {counts['measured']} with a value, "
        f"{counts['null']} null, {counts['not measured']} not measured, {counts['failed']} failed")
    if ctx.attempted:
        log(f"measured this time ({time.monotonic() - started:.0f} s): {' '.join(sorted(ctx.attempted))}")
    log(f"raw results: {ctx.path(ctx.results_dir)}, logs: {ctx.path(ctx.logs_dir)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
