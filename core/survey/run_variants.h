#pragma once
// The estimation variants a run can be made with, as run.yaml,
// calibration.yaml and metrics.json name them (docs/EVALUATE.md):
//   stacked     scan lines stacked side by side: no trajectory, no casting;
//   planar      UHI poses from the INS alone, flat seabed, CAD extrinsic;
//   sequential  the reference paper: SLAM, INS-aligned BA, PnP for every
//               frame, interpolated line poses, extrinsic refined afterwards;
//   joint       one spline, surface, extrinsic and time offset estimated in
//               one global problem.
// (DESIGN.md, "Estimation variants".)
// The readers refuse any other name, so a typo cannot mislabel a benchmark.

#include <string>
#include <string_view>
#include <vector>

namespace hsmap {

inline const std::vector<std::string>& runVariants() {
  static const std::vector<std::string> names = {"stacked", "planar", "sequential", "joint"};
  return names;
}

inline bool isRunVariant(std::string_view name) {
  for (const std::string& variant : runVariants()) {
    if (variant == name) return true;
  }
  return false;
}

// "stacked, planar, sequential, joint", for messages.
inline std::string runVariantList() {
  std::string text;
  for (const std::string& variant : runVariants()) text += (text.empty() ? "" : ", ") + variant;
  return text;
}

}  // namespace hsmap
