#pragma once
// The residual histograms, computed from the files the stages leave in the
// run folder (no stage writes its residuals as such):
//   - reprojection before geo-referencing: every observation of the
//     front-end's map (frontend/keyframes.csv, landmarks.csv,
//     observations.csv) against its landmark projected through the
//     survey's RGB camera;
//   - reprojection after: the same on the adjusted map (georef/, or joint/
//     for the joint variant), which the bundle adjustment's Huber loss
//     down-weights beyond 2 px (its pixel sigma x 2);
//   - INS: every fix's position against the body's position on the run's
//     trajectory at the fix's time (trajectory/frames.csv through
//     survey.yaml's T_B_C), horizontal and in depth; the fixes
//     geo-referencing left out are its outliers.
// The refine and joint stages' tie points are not written to the run
// folder, so they have no histogram (docs/REPORT.md).

#include <filesystem>

#include "pipelines/report/report_data.h"

namespace hsmap {

struct Survey;

// Appends the histograms it can make to data.histograms (needs data.frames
// and data.ins_fixes from collectTrajectory for the INS), notes for those it
// cannot. InputError for a malformed file.
void collectResiduals(const std::filesystem::path& run, const Survey* survey, ReportData& data);

}  // namespace hsmap
