#!/usr/bin/env python3
"""Checks that hsmap's sources keep to its layering (README.md, "Layout").

  scripts/check_layering.py [--root DIR]
      Scans every .h/.hpp/.cc/.cpp under core/, factors/, solvers/,
      pipelines/, tools/, tests/ and benchmarks/ for #include lines.
  scripts/check_layering.py --targets FILE [--root DIR]
      Checks the CMake link graph that cmake/HsmapLayering.cmake writes at
      configure time (one target a line: name, CMakeLists folder, links).

The rules:
  - tools -> pipelines -> solvers -> factors -> core: a layer includes (and
    its CMake targets link) itself and the layers to its right, never a layer
    to its left, tests/ or benchmarks/;
  - core/ includes no Ceres header and links no Ceres target;
  - a project include is a path from the project root ("core/geometry/se3.h"),
    so its layer can be read from it;
  - benchmarks/ includes from tests/ only tests/support/;
  - tests/X includes from tests/ only tests/support/ and its own folder
    tests/X/; tests/ never includes benchmarks/;
  - a pipelines/ folder includes another pipelines/ folder's public headers
    only (PUBLIC_HEADERS below), never its internals;
  - a stage of `hsmap run` (pipelines/run/*_stage.*) never includes another
    stage (stages never call each other: the runner alone knows their order,
    and shared work is a pipeline function in its own folder);
  - tools/ includes from pipelines/ only the entry points (TOOL_ENTRY_POINTS):
    the runner's, the simulator's, the evaluator's and the sample's.

Prints one line per violation, "file:line: includes "x": rule", and exits
with 1 if there is any, 0 if none. Needs no build and no package beyond the
Python standard library. Includes inside /* */ comments are not recognised
as comments (hsmap's sources comment with //).
"""

import argparse
import os
import posixpath
import re
import sys

LAYERS = ["tools", "pipelines", "solvers", "factors", "core"]
ORDER = " \u2192 ".join(LAYERS)
TOP_FOLDERS = LAYERS + ["tests", "benchmarks"]
SOURCE_EXTENSIONS = (".h", ".hh", ".hpp", ".cc", ".cpp", ".cxx")
SUPPORT = "tests/support"
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^">]*)[">]')

# What each pipelines/ folder offers the others; everything else in it is
# its own. A folder not listed offers nothing.
PUBLIC_HEADERS = {
    "frontend": {"frontend_result.h", "frontend_runner.h", "frontend_options.h", "frontend_outputs.h",
                 "visual_map.h", "visual_map_files.h", "frame_pose_estimator.h"},
    "georef": {"georef_result.h", "georef_outputs.h", "georef_options.h", "georef_bundle_adjuster.h",
               "sequential_georef.h", "planar_georef.h", "camera_trajectory.h", "ins_alignment.h",
               "ins_noise.h", "map_placement.h"},
    "surface": {"surface_meshing.h"},
    "products": {"product_casting.h", "hyperspectral_ortho.h", "hyperspectral_point_cloud.h",
                 "stacked_products.h", "rgb_ortho.h", "ortho_grid.h", "ortho_grid_from_header.h",
                 "ortho_accumulator.h", "scan_line_caster.h", "spectrum_validity.h"},
    "calibration": {"extrinsic_refinement.h", "extrinsic_refinement_options.h", "extrinsic_tie_point.h",
                    "extrinsic_from_tie_points.h", "run_tie_points.h", "strip_tie_points.h"},
    "joint": {"joint_problem.h", "joint_solution.h", "joint_spline.h"},
    "radiometry": {"radiometric_observations.h", "water_estimation.h", "reflectance_ortho.h",
                   "radiometry_files.h"},
    "evaluate": {"evaluate_run.h"},
    "report": {"run_report.h"},
    "simulate": {"simulate_survey.h", "simulation_config.h", "simulation_config_yaml.h"},
    "run": {"runner.h", "run_options.h", "stage_table.h", "stage_record.h", "stage_fingerprints.h"},
    "compare": {"compare_runner.h", "variant_list.h"},
}
# What tools/ may include from pipelines/.
TOOL_ENTRY_POINTS = {"pipelines/run/runner.h", "pipelines/run/run_options.h",
                     "pipelines/simulate/simulate_survey.h", "pipelines/simulate/simulation_config.h",
                     "pipelines/simulate/simulation_config_yaml.h", "pipelines/evaluate/evaluate_run.h",
                     "pipelines/report/run_report.h",
                     "pipelines/sample_survey.h", "pipelines/compare/compare_runner.h",
                     "pipelines/compare/variant_list.h"}
STAGE_FILE = re.compile(r"^pipelines/run/(\w+)_stage\.(h|cc)$")


def allowed_layers(layer):
    """The layers `layer` may use: itself and those to its right."""
    return LAYERS[LAYERS.index(layer):]


def in_words(names):
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]


def layer_rule(layer, verb):
    return f"{layer} may {verb} only {in_words(allowed_layers(layer))} ({ORDER})"


def is_ceres(path):
    return path == "ceres" or path.startswith("ceres/")


def include_violation(file_rel, delimiter, included):
    """The rule that `#include <delimiter>included` in file_rel breaks, or None."""
    top = file_rel.split("/", 1)[0]
    if is_ceres(included):
        if top == "core":
            return f"core must not include Ceres (the solver starts at factors: {ORDER})"
        return None
    path = posixpath.normpath(included)
    first = path.split("/", 1)[0]
    if delimiter == "<" and first not in TOP_FOLDERS:
        return None  # a system or third-party header
    if first not in TOP_FOLDERS or "/" not in path:
        return ("not a path from the project root: project includes are \"core/...\", "
                "\"factors/...\", ... (third-party headers take <...>), so their layer can be checked")

    if top in LAYERS:
        if first not in allowed_layers(top):
            return layer_rule(top, "include")
        if first == "pipelines":
            return pipelines_violation(file_rel, path)
    elif top == "benchmarks":
        if first == "tests" and not path.startswith(SUPPORT + "/"):
            return "benchmarks may include from tests/ only tests/support/ (shared test fixtures live there)"
    elif top == "tests":
        own_folder = posixpath.dirname(file_rel)
        if first == "benchmarks":
            return "tests may not include benchmarks/"
        if first == "tests" and not path.startswith(SUPPORT + "/") \
                and posixpath.dirname(path) != own_folder:
            if own_folder.startswith(SUPPORT):
                return "tests/support may include from tests/ only tests/support/ (shared fixtures use no folder's own)"
            return (f"{own_folder} may include from tests/ only tests/support/ and its own folder "
                    f"{own_folder}/ (fixtures shared by several folders live in tests/support/)")
    return None


def pipelines_folder(path):
    """The folder of pipelines/ a path is in ("frontend"), or None for pipelines/x.h."""
    parts = path.split("/")
    return parts[1] if len(parts) > 2 else None


def pipelines_violation(file_rel, path):
    """The pipelines/ rule that file_rel including `path` (under pipelines/) breaks, or None."""
    top = file_rel.split("/", 1)[0]
    if top == "tools":
        if path not in TOOL_ENTRY_POINTS:
            return ("tools may include from pipelines/ only the entry points "
                    + ", ".join(sorted(TOOL_ENTRY_POINTS)) + " (the runner runs the stages)")
        return None
    own, other = pipelines_folder(file_rel), pipelines_folder(path)
    stage, included_stage = STAGE_FILE.match(file_rel), STAGE_FILE.match(path)
    if stage and included_stage and stage.group(1) != included_stage.group(1):
        return (f"the {stage.group(1)} stage calls the {included_stage.group(1)} stage: stages never call "
                "each other (the runner alone knows their order; shared work is a pipeline function)")
    if other is None or own == other:
        return None
    if posixpath.basename(path) not in PUBLIC_HEADERS.get(other, set()):
        return (f"includes an internal header of pipelines/{other}/: a pipelines folder may include "
                f"another's public headers only (PUBLIC_HEADERS in scripts/check_layering.py)")
    return None


def source_files(root):
    for top in TOP_FOLDERS:
        top_dir = os.path.join(root, top)
        for folder, subfolders, files in os.walk(top_dir):
            subfolders[:] = sorted(d for d in subfolders if not d.startswith("."))
            for name in sorted(files):
                if name.endswith(SOURCE_EXTENSIONS):
                    path = os.path.join(folder, name)
                    yield path, os.path.relpath(path, root).replace(os.sep, "/")


def check_includes(root):
    violations = []
    count = 0
    for path, rel in source_files(root):
        count += 1
        with open(path, encoding="utf-8", errors="replace") as source:
            for number, line in enumerate(source, start=1):
                match = INCLUDE.match(line)
                if not match:
                    continue
                delimiter, included = match.groups()
                rule = include_violation(rel, delimiter, included)
                if rule:
                    closing = '"' if delimiter == '"' else ">"
                    violations.append((rel, number,
                                       f"{rel}:{number}: includes {delimiter}{included}{closing}: {rule}"))
    return count, [message for _, _, message in sorted(violations)]


LINK_ONLY = re.compile(r"^\$<LINK_ONLY:(.*)>$")


def check_targets(root, targets_file):
    """Checks the link graph: name<TAB>folder of its CMakeLists.txt<TAB>links (;-separated)."""
    folders = {}
    links = {}
    with open(targets_file, encoding="utf-8") as table:
        for line in table:
            fields = line.rstrip("\n").split("\t")
            if len(fields) != 3:
                continue
            name, folder, linked = fields
            rel = os.path.relpath(folder, root).replace(os.sep, "/")
            folders[name] = rel
            links[name] = [item for item in linked.split(";") if item]

    violations = []
    for name in sorted(folders, key=lambda name: (folders[name], name)):
        top = folders[name].split("/", 1)[0]
        if top not in LAYERS:
            continue
        where = f"{folders[name]}/CMakeLists.txt: target {name}"
        for item in dict.fromkeys(links[name]):
            match = LINK_ONLY.match(item)
            dependency = match.group(1) if match else item
            if top == "core" and (dependency.lower().startswith("ceres::") or dependency == "ceres"):
                violations.append(f"{where} links {dependency}: core must not link Ceres "
                                  f"(the solver starts at factors: {ORDER})")
            elif dependency in folders:
                dependency_top = folders[dependency].split("/", 1)[0]
                if dependency_top not in allowed_layers(top):
                    violations.append(f"{where} links {dependency} ({folders[dependency]}): "
                                      f"{layer_rule(top, 'link')}")
    return len(folders), violations


def main():
    default_root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--root", default=default_root, help="the project root (default: %(default)s)")
    parser.add_argument("--targets", metavar="FILE",
                        help="check this CMake link graph instead of the includes")
    args = parser.parse_args()
    root = os.path.abspath(args.root)

    if args.targets:
        count, violations = check_targets(root, args.targets)
        what = "CMake targets"
    else:
        count, violations = check_includes(root)
        what = "source files"
    for violation in violations:
        print(violation)
    if violations:
        print(f"layering: {len(violations)} violation(s) in {count} {what} (README.md, \"Layout\")")
        return 1
    print(f"layering: {count} {what} checked, no violation")
    return 0


if __name__ == "__main__":
    sys.exit(main())
