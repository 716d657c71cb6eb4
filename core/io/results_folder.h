#pragma once
// ResultsFolder: the results folder of one run (`hsmap run ... --out RUN`,
// DATASET.md "Results folder"). It knows the products' relative paths,
// creates sub-folders on demand and hands out AtomicFile writers, so that a
// product exists under its final name only once it is complete.
//
// Relative paths must stay inside the folder: absolute paths and `..`
// components are programming errors (std::invalid_argument).

#include <filesystem>

#include "core/io/atomic_file.h"

namespace hsmap {

// Relative paths of the products, as in DATASET.md.
namespace results_paths {
inline constexpr const char* run_yaml = "run.yaml";
inline constexpr const char* trajectory_frames = "trajectory/frames.csv";
inline constexpr const char* trajectory_uhi_lines = "trajectory/uhi_lines.csv";
inline constexpr const char* calibration_yaml = "calibration.yaml";
inline constexpr const char* sparse_ply = "map/sparse.ply";
inline constexpr const char* mesh_ply = "map/mesh.ply";
inline constexpr const char* ortho_hdr = "hyperspectral/ortho.hdr";
inline constexpr const char* ancillary_hdr = "hyperspectral/ancillary.hdr";
inline constexpr const char* ortho_rgb_png = "hyperspectral/ortho_rgb.png";
inline constexpr const char* report_dir = "report";
inline constexpr const char* metrics_json = "metrics.json";
}  // namespace results_paths

class ResultsFolder {
 public:
  // Creates `root` (and its parents) if needed; std::runtime_error if that fails.
  explicit ResultsFolder(std::filesystem::path root);

  const std::filesystem::path& root() const { return root_; }

  // root / relative_path, with its parent folders created. For writers that
  // manage their own temporary names (EnviWriter, writePly).
  std::filesystem::path prepare(const std::filesystem::path& relative_path) const;

  // An AtomicFile for root / relative_path, parent folders created.
  AtomicFile product(const std::filesystem::path& relative_path,
                     AtomicFile::Mode mode = AtomicFile::Mode::stream) const;

 private:
  std::filesystem::path root_;
};

}  // namespace hsmap
