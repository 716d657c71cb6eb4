#!/usr/bin/env bash
# CTest report.browser: `hsmap run` on a simulated `tiny` survey, `hsmap
# evaluate` (which refreshes the report with the metrics), then
# RUN/report/index.html loaded in headless Chromium by
# check_report_in_browser.cjs: no request, no console error, every plot
# rendered (checked in the DOM), and a screenshot written.
#
#   report_in_browser_test.sh HSMAP NODE NODE_MODULES WORK_DIR SCREENSHOT_PNG
set -euo pipefail
hsmap=$1 node=$2 modules=$3 work=$4 screenshot=$5
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
rm -rf "$work"
mkdir -p "$work"
"$hsmap" simulate --preset tiny --out "$work/survey" > "$work/simulate.log"
"$hsmap" run "$work/survey" --out "$work/run" > "$work/run.log"
grep -qx "report: $work/run/report/index.html" "$work/run.log" ||
  { echo "FAIL: hsmap run did not print 'report: $work/run/report/index.html'"; tail -5 "$work/run.log"; exit 1; }
"$hsmap" evaluate "$work/run" --truth "$work/survey/truth" > "$work/evaluate.log"
grep -q "^report: $work/run/report/index.html (with the metrics)" "$work/evaluate.log" ||
  { echo "FAIL: hsmap evaluate did not refresh the report"; tail -5 "$work/evaluate.log"; exit 1; }
echo "report: $(stat -c %s "$work/run/report/index.html") bytes"
"$node" "$here/check_report_in_browser.cjs" "$modules" "$work/run/report/index.html" "$screenshot" --expect-metrics
