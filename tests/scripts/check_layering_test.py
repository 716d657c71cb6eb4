#!/usr/bin/env python3
"""Tests scripts/check_layering.py on tiny source trees: a clean tree passes,
and a tree with one violation of each rule fails naming each file:line, the
include and the rule it breaks. Run by CTest as layering.checker."""

import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
CHECKER = os.path.join(HERE, "..", "..", "scripts", "check_layering.py")
ORDER = "(tools \u2192 pipelines \u2192 solvers \u2192 factors \u2192 core)"


def write_tree(root, files):
    for path, text in files.items():
        full = os.path.join(root, path)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        with open(full, "w", encoding="utf-8") as out:
            out.write(text)


def run_checker(*args):
    result = subprocess.run([sys.executable, CHECKER, *args], capture_output=True,
                            text=True, encoding="utf-8")
    return result.returncode, result.stdout.splitlines()


CLEAN_TREE = {
    "core/util/a.h": '#pragma once\n#include <Eigen/Core>\n#include "core/util/b.h"\n'
                     '// #include "solvers/s.h" is only a comment\n',
    "core/util/b.h": "#pragma once\n#include <vector>\n",
    "factors/f.h": '#pragma once\n#include <ceres/ceres.h>\n#include "core/util/a.h"\n',
    "solvers/s.h": '#pragma once\n#include "factors/f.h"\n#include "core/util/a.h"\n',
    "pipelines/stage/p.cc": '#include "pipelines/stage/p.h"\n#include "solvers/s.h"\n',
    "pipelines/stage/p.h": "#pragma once\n",
    "tools/hsmap/main.cpp": '#  include "pipelines/run/runner.h"\n#include "tools/hsmap/cli.h"\n',
    "pipelines/run/runner.h": "#pragma once\n",
    "pipelines/run/surface_stage.cc": '#include "pipelines/run/surface_stage.h"\n'
                                      '#include "pipelines/surface/surface_meshing.h"\n',
    "pipelines/run/surface_stage.h": "#pragma once\n",
    "pipelines/surface/surface_meshing.h": '#pragma once\n#include "pipelines/frontend/visual_map.h"\n',
    "tools/hsmap/cli.h": "#pragma once\n",
    "tests/support/fixture.h": '#pragma once\n#include "solvers/s.h"\n#include "tests/support/other.h"\n',
    "tests/support/other.h": "#pragma once\n",
    "tests/solvers/own.h": '#pragma once\n#include "tests/support/fixture.h"\n',
    "tests/solvers/s_test.cc": '#include "tests/solvers/own.h"\n#include "tests/support/fixture.h"\n'
                               '#include "pipelines/stage/p.h"\n',
    "benchmarks/s_bench.cc": '#include "tests/support/fixture.h"\n#include "tools/hsmap/cli.h"\n',
    "build/core/generated.h": '#include "tools/hsmap/cli.h"\n',  # not a source folder
    "core/util/notes.txt": '#include "solvers/s.h"\n',  # not a source file
}

# One violation of each kind (and the line it is on).
VIOLATIONS_TREE = {
    "core/geometry/foo.h": '#pragma once\n#include "solvers/bar.h"\n',
    "core/util/uses_ceres.cc": '#include <vector>\n\n#include <ceres/ceres.h>\n',
    "core/io/test_helper.h": '#include "tests/support/temp_folder.h"\n',
    "factors/f.h": '#include "core/util/a.h"\n#include "pipelines/stage/p.h"\n',
    "factors/relative.h": '#include "../core/util/a.h"\n#include "a.h"\n#include "Eigen/Core"\n',
    "solvers/s.cc": '#include <core/util/a.h>\n#include <tools/hsmap/cli.h>\n',
    "pipelines/stage/p.cc": '#include "benchmarks/timer.h"\n',
    "benchmarks/engine_bench.cc": '#include "tests/support/ok.h"\n#include "tests/solvers/transect.h"\n',
    "tests/pipelines/frontend/x_test.cc": '#include "tests/pipelines/frontend/own.h"\n'
                                          '#include "tests/solvers/transect.h"\n',
    "tests/pipelines/y_test.cc": '#include "tests/pipelines/frontend/own.h"\n',
    "tests/core/z_test.cc": '#include "benchmarks/timer.h"\n',
    "tests/support/fixture.h": '#include "tests/core/geometry/numeric.h"\n',
    # The planted edges of the pipelines rules: a stage calling another, a
    # folder using another's internals, the command line reaching past the
    # runner.
    "pipelines/run/joint_stage.cc": '#include "pipelines/run/joint_stage.h"\n'
                                    '#include "pipelines/run/surface_stage.h"\n',
    "pipelines/surface/dense_surface.cc": '#include "pipelines/frontend/visual_map.h"\n'
                                          '#include "pipelines/frontend/klt_tracker.h"\n',
    "tools/hsmap/run_command.cc": '#include "pipelines/run/runner.h"\n'
                                  '#include "pipelines/georef/georef_outputs.h"\n',
}

EXPECTED_VIOLATIONS = [
    f'benchmarks/engine_bench.cc:2: includes "tests/solvers/transect.h": benchmarks may include '
    f'from tests/ only tests/support/ (shared test fixtures live there)',
    f'core/geometry/foo.h:2: includes "solvers/bar.h": core may include only core {ORDER}',
    f'core/io/test_helper.h:1: includes "tests/support/temp_folder.h": core may include only core {ORDER}',
    f'core/util/uses_ceres.cc:3: includes <ceres/ceres.h>: core must not include Ceres '
    f'(the solver starts at factors: tools \u2192 pipelines \u2192 solvers \u2192 factors \u2192 core)',
    f'factors/f.h:2: includes "pipelines/stage/p.h": factors may include only factors and core {ORDER}',
    'factors/relative.h:1: includes "../core/util/a.h": not a path from the project root: project '
    'includes are "core/...", "factors/...", ... (third-party headers take <...>), so their layer '
    'can be checked',
    'factors/relative.h:2: includes "a.h": not a path from the project root: project includes are '
    '"core/...", "factors/...", ... (third-party headers take <...>), so their layer can be checked',
    'factors/relative.h:3: includes "Eigen/Core": not a path from the project root: project includes '
    'are "core/...", "factors/...", ... (third-party headers take <...>), so their layer can be checked',
    'pipelines/run/joint_stage.cc:2: includes "pipelines/run/surface_stage.h": the joint stage calls the '
    'surface stage: stages never call each other (the runner alone knows their order; shared work is a '
    'pipeline function)',
    f'pipelines/stage/p.cc:1: includes "benchmarks/timer.h": pipelines may include only pipelines, '
    f'solvers, factors and core {ORDER}',
    'pipelines/surface/dense_surface.cc:2: includes "pipelines/frontend/klt_tracker.h": includes an '
    'internal header of pipelines/frontend/: a pipelines folder may include another\'s public headers '
    'only (PUBLIC_HEADERS in scripts/check_layering.py)',
    f'solvers/s.cc:2: includes <tools/hsmap/cli.h>: solvers may include only solvers, factors and '
    f'core {ORDER}',
    'tests/core/z_test.cc:1: includes "benchmarks/timer.h": tests may not include benchmarks/',
    'tests/pipelines/frontend/x_test.cc:2: includes "tests/solvers/transect.h": tests/pipelines/frontend '
    'may include from tests/ only tests/support/ and its own folder tests/pipelines/frontend/ '
    '(fixtures shared by several folders live in tests/support/)',
    'tests/pipelines/y_test.cc:1: includes "tests/pipelines/frontend/own.h": tests/pipelines may '
    'include from tests/ only tests/support/ and its own folder tests/pipelines/ (fixtures shared '
    'by several folders live in tests/support/)',
    'tests/support/fixture.h:1: includes "tests/core/geometry/numeric.h": tests/support may include '
    "from tests/ only tests/support/ (shared fixtures use no folder's own)",
    'tools/hsmap/run_command.cc:2: includes "pipelines/georef/georef_outputs.h": tools may include from '
    'pipelines/ only the entry points pipelines/compare/compare_runner.h, pipelines/compare/variant_list.h, '
    'pipelines/evaluate/evaluate_run.h, pipelines/report/run_report.h, '
    'pipelines/run/run_options.h, pipelines/run/runner.h, pipelines/sample_survey.h, pipelines/simulate/simulate_survey.h, '
    'pipelines/simulate/simulation_config.h, pipelines/simulate/simulation_config_yaml.h (the runner '
    'runs the stages)',
]


class IncludeCheck(unittest.TestCase):
    def test_clean_tree_passes(self):
        with tempfile.TemporaryDirectory() as root:
            write_tree(root, CLEAN_TREE)
            code, lines = run_checker("--root", root)
        self.assertEqual(lines, ["layering: 17 source files checked, no violation"])
        self.assertEqual(code, 0)

    def test_each_violation_is_named_with_file_line_include_and_rule(self):
        with tempfile.TemporaryDirectory() as root:
            write_tree(root, VIOLATIONS_TREE)
            code, lines = run_checker("--root", root)
        self.assertEqual(code, 1)
        self.assertEqual(lines, EXPECTED_VIOLATIONS + [
            f'layering: {len(EXPECTED_VIOLATIONS)} violation(s) in 15 source files (README.md, "Layout")'])


class TargetCheck(unittest.TestCase):
    def check(self, rows):
        with tempfile.TemporaryDirectory() as root:
            table = os.path.join(root, "links.tsv")
            with open(table, "w", encoding="utf-8") as out:
                for name, folder, links in rows:
                    out.write(f"{name}\t{os.path.join(root, folder)}\t{links}\n")
            return run_checker("--root", root, "--targets", table)

    CLEAN = [
        ("hsmap_util", "core", "Eigen3::Eigen;Threads::Threads"),
        ("hsmap_geometry", "core", "hsmap_util;$<LINK_ONLY:hsmap_util>"),
        ("hsmap_factors", "factors", "hsmap_geometry;Ceres::ceres"),
        ("hsmap_solvers", "solvers", "hsmap_factors;Ceres::ceres"),
        ("hsmap_pipelines", "pipelines", "hsmap_solvers;hsmap_util"),
        ("hsmap", "tools", "hsmap_pipelines;CLI11::CLI11"),
        ("hsmap_test_support", "tests/support", ""),
        ("test_core_survey", "tests", "hsmap_pipelines;hsmap_test_support"),
        ("engine_bench", "benchmarks", "hsmap_pipelines;hsmap_test_support"),
    ]

    def test_clean_graph_passes(self):
        code, lines = self.check(self.CLEAN)
        self.assertEqual(lines, ["layering: 9 CMake targets checked, no violation"])
        self.assertEqual(code, 0)

    def test_backward_links_and_ceres_in_core_are_named(self):
        rows = self.CLEAN + [
            ("hsmap_raycast", "core", "hsmap_util;Ceres::ceres"),
            ("hsmap_graph", "core", "$<LINK_ONLY:hsmap_factors>"),
            ("hsmap_frontend", "pipelines", "hsmap_solvers;hsmap"),
            ("hsmap_fixtures_user", "solvers", "hsmap_test_support"),
        ]
        code, lines = self.check(rows)
        self.assertEqual(code, 1)
        self.assertEqual(lines, [
            f"core/CMakeLists.txt: target hsmap_graph links hsmap_factors (factors): core may link "
            f"only core {ORDER}",
            "core/CMakeLists.txt: target hsmap_raycast links Ceres::ceres: core must not link Ceres "
            "(the solver starts at factors: tools \u2192 pipelines \u2192 solvers \u2192 factors "
            "\u2192 core)",
            f"pipelines/CMakeLists.txt: target hsmap_frontend links hsmap (tools): pipelines may "
            f"link only pipelines, solvers, factors and core {ORDER}",
            f"solvers/CMakeLists.txt: target hsmap_fixtures_user links hsmap_test_support "
            f"(tests/support): solvers may link only solvers, factors and core {ORDER}",
            'layering: 4 violation(s) in 13 CMake targets (README.md, "Layout")',
        ])


if __name__ == "__main__":
    unittest.main()
