#include "pipelines/run/run_options.h"

#include <cmath>
#include <stdexcept>

#include "core/survey/number_text.h"
#include "pipelines/products/hyperspectral_point_cloud.h"

namespace hsmap {

namespace {

[[noreturn]] void invalid(const std::string& option, const std::string& expected, const std::string& got) {
  throw std::invalid_argument(option + ": expected " + expected + ", got " + got);
}

}  // namespace

const char* toString(Variant variant) {
  switch (variant) {
    case Variant::sequential: return "sequential";
    case Variant::planar: return "planar";
    case Variant::stacked: return "stacked";
    case Variant::joint: return "joint";
  }
  return "?";
}

Variant parseVariant(const std::string& text) {
  for (Variant v : {Variant::sequential, Variant::planar, Variant::stacked, Variant::joint}) {
    if (text == toString(v)) return v;
  }
  invalid("--variant", "one of sequential, planar, stacked, joint", "'" + text + "'");
}

const char* toString(JointTiePoints source) {
  return source == JointTiePoints::strip ? "strip" : "ortho";
}

JointTiePoints parseJointTiePoints(const std::string& text) {
  if (text == "strip") return JointTiePoints::strip;
  if (text == "ortho") return JointTiePoints::ortho;
  invalid("--joint-tie-points", "strip or ortho", "'" + text + "'");
}

SurfaceMode parseSurfaceMode(const std::string& text) {
  if (text == "dense") return SurfaceMode::dense;
  if (text == "sparse") return SurfaceMode::sparse;
  invalid("--surface", "dense or sparse", "'" + text + "'");
}

void SurfaceStageOptions::validate() const {
  if (seabed_depth_m && !std::isfinite(*seabed_depth_m)) {
    invalid("--seabed-depth", "a finite depth in metres", formatDouble(*seabed_depth_m));
  }
}

void RefineStageOptions::validate() const {
  if (rounds < 0 || rounds > kMaxRounds) {
    invalid("--extrinsic-rounds", "0 to " + std::to_string(kMaxRounds), std::to_string(rounds));
  }
  if (!(cast_pixel_m > 0.0) || !std::isfinite(cast_pixel_m)) {
    invalid("refine cast_pixel_m", "a pixel size > 0 m", formatDouble(cast_pixel_m));
  }
}

void JointStageOptions::validate() const {
  if (rounds < 1 || rounds > kMaxRounds) {
    invalid("--joint-rounds", "1 to " + std::to_string(kMaxRounds), std::to_string(rounds));
  }
  if (!(cast_pixel_m > 0.0) || !std::isfinite(cast_pixel_m)) {
    invalid("joint cast_pixel_m", "a pixel size > 0 m", formatDouble(cast_pixel_m));
  }
  for (const auto& [name, value] : {std::pair{"joint ortho_patch_spacing_m", ortho_patch_spacing_m},
                                    std::pair{"joint strip_sigma_match_m", strip_sigma_match_m},
                                    std::pair{"joint strip_sigma_match_along_m", strip_sigma_match_along_m}}) {
    if (!(value > 0.0) || !std::isfinite(value)) invalid(name, "a length > 0 m", formatDouble(value));
  }
}

void ProductsStageOptions::validate() const {
  if (!(ortho_pixel_m > 0.0) || !std::isfinite(ortho_pixel_m)) {
    invalid("--ortho-pixel", "a pixel size > 0 m", formatDouble(ortho_pixel_m));
  }
  if (points && !(point_cell_m >= HyperspectralPointCloudOptions::kMinCellM &&
                  point_cell_m <= HyperspectralPointCloudOptions::kMaxCellM)) {
    invalid("--point-cell",
            "a cell size between " + formatDouble(HyperspectralPointCloudOptions::kMinCellM) + " and " +
                formatDouble(HyperspectralPointCloudOptions::kMaxCellM) + " m (default " +
                formatDouble(ProductsStageOptions{}.point_cell_m) + "; --no-points skips the point cloud)",
            formatDouble(point_cell_m));
  }
}

void RunOptions::validate() const {
  if (threads < 0) invalid("--threads", "a thread count >= 0 (0: every hardware thread)", std::to_string(threads));
  surface.validate();
  refine.validate();
  joint.validate();
  products.validate();
}

}  // namespace hsmap
