#pragma once
// The front-end's frames against the truth after the best similarity
// (Umeyama on the posed frames' positions): its shape error, as the
// front-end tests and benchmarks/frontend_measure_tool report it. Needs
// hsmap_frontend and core.

#include <cmath>
#include <vector>

#include "core/geometry/sim3.h"
#include "core/survey/truth_files.h"
#include "pipelines/frontend/frontend_result.h"

namespace hsmap::testing {

struct AlignedError {
  int pairs = 0;
  double rms_m = 0.0;
  double path_length_m = 0.0;
  double scale = 1.0;
  double percentOfPath() const { return path_length_m > 0.0 ? 100.0 * rms_m / path_length_m : 0.0; }
};

// Sim(3) alignment (Umeyama) of the posed frames' positions onto the truth.
inline AlignedError alignedFrameError(const FrontendResult& result, const std::vector<TruthPose>& truth) {
  std::vector<Eigen::Vector3d> source, target;
  for (const FrameRecord& frame : result.frames) {
    if (!frame.posed) continue;
    source.push_back(frame.T_F_C.t);
    target.push_back(truth.at(std::size_t(frame.index)).T_W_X.t);
  }
  AlignedError error;
  error.pairs = int(source.size());
  for (std::size_t i = 1; i < truth.size(); ++i) error.path_length_m += (truth[i].T_W_X.t - truth[i - 1].T_W_X.t).norm();
  if (source.size() < 3) return error;
  const Sim3 S = alignUmeyama(source, target, true);
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < source.size(); ++i) sum_sq += (S.apply(source[i]) - target[i]).squaredNorm();
  error.rms_m = std::sqrt(sum_sq / double(source.size()));
  error.scale = S.scale();
  return error;
}

}  // namespace hsmap::testing
