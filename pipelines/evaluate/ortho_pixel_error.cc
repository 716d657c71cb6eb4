#include "pipelines/evaluate/ortho_pixel_error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include <Eigen/LU>

#include "core/geometry/pose_interpolation.h"
#include "core/geometry/utm_projection.h"
#include "core/io/envi_ignore_value.h"
#include "core/io/envi_reader.h"
#include "core/util/input_error.h"
#include "pipelines/evaluate/ortho_metrics.h"
#include "pipelines/evaluate/ortho_raster_grid.h"

namespace hsmap {

namespace {
constexpr double kLineRounding = 1e-3;  // lines
}  // namespace
namespace {

// The UTM -> W map is evaluated exactly every kNodeStep pixels along a row.
constexpr int kNodeStep = 16;

// The sums one patch contributes: its pixel count, the sums of the true
// seen points q and pixel centres c (east, north, relative to the raster's
// centre), and the normal equations of the similarity c = [p -q; q p] q + t
// in the unknowns (p, q, t_east, t_north).
struct PatchSums {
  std::int64_t named = 0;     // pixels naming a line and sample
  std::int64_t measured = 0;  // of those, with a true seen point
  Eigen::Vector2d sum_seen = Eigen::Vector2d::Zero();
  Eigen::Vector2d sum_centre = Eigen::Vector2d::Zero();
  Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();  // A^T A
  Eigen::Vector4d rhs = Eigen::Vector4d::Zero();     // A^T c
  std::string first_error;                           // first out-of-range pixel, if any
  int error_row = 0, error_col = 0;

  void add(const Eigen::Vector2d& seen, const Eigen::Vector2d& centre) {
    ++measured;
    sum_seen += seen;
    sum_centre += centre;
    Eigen::Matrix<double, 2, 4> A;
    A << seen.x(), -seen.y(), 1.0, 0.0,  //
        seen.y(), seen.x(), 0.0, 1.0;
    normal += A.transpose() * A;
    rhs += A.transpose() * centre;
  }
};

// One band of patches: rows [row0, row0 + side) of the ancillary layer's
// line and sample bands, and every pixel centre's (east, north) in W
// relative to the raster's centre.
struct PatchBand {
  int row0 = 0;
  Eigen::MatrixXf line, sample;              // side x cols
  std::vector<Eigen::Vector2d> centres_EN;   // side * cols, row-major
};

std::string pixelName(int row, int col) {
  return "pixel (row " + std::to_string(row) + ", column " + std::to_string(col) + ")";
}

}  // namespace

void OrthoPixelErrorOptions::validate() const {
  const auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("OrthoPixelErrorOptions: ") + what);
  };
  require(std::isfinite(patch_size_m) && patch_size_m > 0.0, "patch_size_m must be finite and > 0");
  require(min_patch_pixels >= 1, "min_patch_pixels must be >= 1");
  require(min_measured_fraction > 0.0 && min_measured_fraction <= 1.0,
          "min_measured_fraction must be in (0, 1]");
}

std::string OrthoPixelError::summary() const {
  std::ostringstream out;
  out.precision(6);
  out << "ortho pixels: " << pixels_named << " name a scan line and sample, " << pixels_measured
      << " seen on the true surface; " << patches_measured << " of " << patches << " patches of "
      << patch_pixels << " px measured";
  if (scale && rotation_deg) {
    out << "; removed similarity: scale " << *scale << ", rotation " << *rotation_deg << " deg";
  }
  if (mean_displacement_NE) {
    out << ", mean displacement (north, east) = (" << mean_displacement_NE->x() << ", "
        << mean_displacement_NE->y() << ") m";
  }
  return out.str();
}

OrthoPixelError measureOrthoPixelError(const std::filesystem::path& ancillary_hdr,
                                       const std::vector<SE3d>& T_W_U_true,
                                       const PushbroomCamera& camera_true,
                                       const MeshRayCaster& true_scene, const GeodeticPoint& origin,
                                       const OrthoPixelErrorOptions& options) {
  options.validate();
  if (T_W_U_true.empty()) throw std::invalid_argument("measureOrthoPixelError: no line pose");
  const UtmProjection utm(origin);
  const EnviReader reader(ancillary_hdr);
  const RasterGrid grid = utmRasterGrid(reader.header(), reader.headerPath(), utm);
  if (reader.bands() < 2) {
    throw InputError(ancillary_hdr, InputError::atKey("bands"),
                     std::to_string(reader.bands()) +
                         ": expected at least 2 (scan line, sample, range, incidence; docs/PRODUCTS.md)");
  }
  const std::optional<float> ignore = enviDataIgnoreValue(reader.header(), ancillary_hdr);
  const auto named = [&](float v) { return std::isfinite(v) && !(ignore && v == *ignore); };

  OrthoPixelError result;
  const int side = std::max(options.min_patch_pixels,
                            static_cast<int>(std::lround(options.patch_size_m / grid.px)));
  result.patch_pixels = side;
  const int patch_rows = grid.rows / side, patch_cols = grid.cols / side;
  result.patches = patch_rows * patch_cols;
  const int top = (grid.rows - patch_rows * side) / 2, left = (grid.cols - patch_cols * side) / 2;
  // Coordinates relative to the raster's centre keep the normal equations
  // well conditioned wherever W's origin is.
  const Eigen::Vector2d raster_centre = grid.centre(0.5 * (grid.rows - 1), 0.5 * (grid.cols - 1));
  const Eigen::Vector3d centre_W = utm.utmToNed(raster_centre.x(), raster_centre.y(), 0.0);
  const Eigen::Vector2d reference_EN(centre_W.y(), centre_W.x());
  const double last_line = static_cast<double>(T_W_U_true.size() - 1);

  std::vector<PatchSums> sums(static_cast<std::size_t>(result.patches));
  PatchBand band;
  band.line.resize(side, grid.cols);
  band.sample.resize(side, grid.cols);
  band.centres_EN.resize(static_cast<std::size_t>(side) * grid.cols);
  Eigen::MatrixXf values;  // bands x cols
  for (int pr = 0; pr < patch_rows; ++pr) {
    band.row0 = top + pr * side;
    for (int i = 0; i < side; ++i) {
      reader.readLine(band.row0 + i, values);
      band.line.row(i) = values.row(0);
      band.sample.row(i) = values.row(1);
    }
    // Pixel centres in W: exact at the nodes, linear in between.
    tbb::parallel_for(0, side, [&](int i) {
      const int row = band.row0 + i;
      const auto exact = [&](int col) -> Eigen::Vector2d {
        const Eigen::Vector2d en = grid.centre(row, col);
        const Eigen::Vector3d p_W = utm.utmToNed(en.x(), en.y(), 0.0);
        return Eigen::Vector2d(p_W.y(), p_W.x()) - reference_EN;
      };
      Eigen::Vector2d* out = &band.centres_EN[static_cast<std::size_t>(i) * grid.cols];
      for (int c0 = 0; c0 < grid.cols; c0 += kNodeStep) {
        const int c1 = std::min(c0 + kNodeStep, grid.cols - 1);
        const Eigen::Vector2d a = exact(c0), b = c1 > c0 ? exact(c1) : a;
        for (int c = c0; c < std::min(c0 + kNodeStep, grid.cols); ++c) {
          const double w = c1 > c0 ? static_cast<double>(c - c0) / (c1 - c0) : 0.0;
          out[c] = (1.0 - w) * a + w * b;
        }
      }
    });
    tbb::parallel_for(tbb::blocked_range<int>(0, patch_cols), [&](const tbb::blocked_range<int>& range) {
      std::vector<Ray> rays;
      std::vector<RayHit> hits;
      std::vector<Eigen::Vector2d> centres;
      for (int pc = range.begin(); pc != range.end(); ++pc) {
        PatchSums& patch = sums[static_cast<std::size_t>(pr) * patch_cols + pc];
        rays.clear();
        centres.clear();
        for (int i = 0; i < side; ++i) {
          for (int c = left + pc * side; c < left + (pc + 1) * side; ++c) {
            float l = band.line(i, c);
            const float u = band.sample(i, c);
            if (!named(l) || !named(u)) continue;
            ++patch.named;
            // A gap-filled pixel's line, interpolated and stored as float32,
            // may pass the first or last line by a rounding (1440.000122 for
            // 1440 on rugged): within a thousandth of a line it is that line.
            if (l < 0.0f && l > -kLineRounding) l = 0.0f;
            if (l > last_line && l < last_line + kLineRounding) l = float(last_line);
            const bool line_ok = l >= 0.0f && l <= last_line;
            if (!line_ok || !camera_true.isInLine(u)) {
              if (patch.first_error.empty()) {
                patch.error_row = band.row0 + i;
                patch.error_col = c;
                std::ostringstream why;
                why.precision(10);
                if (!line_ok) {
                  why << "scan line " << l << " out of range: expected 0 to " << last_line
                      << " (the survey's scan lines)";
                } else {
                  why << "sample " << u << " out of range: expected -0.5 to "
                      << camera_true.samples() - 0.5 << " (the UHI camera's samples)";
                }
                patch.first_error = why.str();
              }
              continue;
            }
            const std::optional<Eigen::Vector3d> ray_U = camera_true.unproject(u);
            if (!ray_U) continue;  // beyond the distortion's fold: no ray
            const auto k = static_cast<std::size_t>(std::floor(l));
            const double fraction = l - static_cast<double>(k);
            const SE3d T_W_U = fraction > 0.0 ? interpolatePose(T_W_U_true[k], T_W_U_true[k + 1], fraction)
                                              : T_W_U_true[k];
            Ray ray;
            ray.origin = T_W_U.t;
            ray.direction = T_W_U.q * *ray_U;
            rays.push_back(ray);
            centres.push_back(band.centres_EN[static_cast<std::size_t>(i) * grid.cols + c]);
          }
        }
        hits.resize(rays.size());
        true_scene.intersect(rays, hits);
        for (std::size_t j = 0; j < rays.size(); ++j) {
          if (!hits[j].hit()) continue;
          const Eigen::Vector3d q_W = rays[j].origin + hits[j].distance * rays[j].direction;
          patch.add(Eigen::Vector2d(q_W.y(), q_W.x()) - reference_EN, centres[j]);
        }
      }
    });
  }
  // The first bad pixel in raster order (patches are in raster order of
  // their first row, so compare positions).
  const PatchSums* bad = nullptr;
  for (const PatchSums& patch : sums) {
    if (patch.first_error.empty()) continue;
    if (!bad || std::pair(patch.error_row, patch.error_col) < std::pair(bad->error_row, bad->error_col)) {
      bad = &patch;
    }
  }
  if (bad) throw InputError(ancillary_hdr, pixelName(bad->error_row, bad->error_col), bad->first_error);

  const auto enough = static_cast<std::int64_t>(std::ceil(options.min_measured_fraction * side * side));
  Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
  Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
  Eigen::Vector2d sum_displacement = Eigen::Vector2d::Zero();
  double abs_sum2 = 0.0;
  for (const PatchSums& patch : sums) {
    result.pixels_named += patch.named;
    result.pixels_measured += patch.measured;
    if (patch.measured < enough) continue;
    ++result.patches_measured;
    normal += patch.normal;
    rhs += patch.rhs;
    const Eigen::Vector2d mean_d = (patch.sum_centre - patch.sum_seen) / static_cast<double>(patch.measured);
    sum_displacement += mean_d;
    abs_sum2 += mean_d.squaredNorm();
  }
  if (result.patches_measured == 0) {
    std::ostringstream why;
    why << "no ortho patch has " << 100.0 * options.min_measured_fraction
        << " % of its pixels seen on the true surface (" << result.pixels_named
        << " pixels name a scan line and sample, " << result.pixels_measured << " seen; "
        << result.patches << " patches of " << side << " px)";
    result.ortho_pixel_error_m = result.ortho_pixel_error_abs_m = MetricValue::missing(why.str());
    return result;
  }
  const double patches_measured = result.patches_measured;
  result.ortho_pixel_error_abs_m = MetricValue::of(std::sqrt(abs_sum2 / patches_measured));
  const Eigen::Vector2d mean_EN = sum_displacement / patches_measured;
  result.mean_displacement_NE = Eigen::Vector2d(mean_EN.y(), mean_EN.x());

  const Eigen::FullPivLU<Eigen::Matrix4d> lu(normal);
  if (lu.rank() < 4) {
    result.ortho_pixel_error_m = MetricValue::missing(
        "the measured pixels all see one point: no similarity to remove");
    return result;
  }
  const Eigen::Vector4d x = lu.solve(rhs);  // (p, q, t_east, t_north)
  Eigen::Matrix2d M;
  M << x(0), -x(1), x(1), x(0);
  const Eigen::Vector2d t = x.tail<2>();
  result.scale = std::hypot(x(0), x(1));
  result.rotation_deg = std::atan2(x(1), x(0)) * 180.0 / std::numbers::pi;
  // The residual c - S q is linear in q and c, so its patch mean is that of
  // the patch's means.
  double sum2 = 0.0;
  for (const PatchSums& patch : sums) {
    if (patch.measured < enough) continue;
    const double n = static_cast<double>(patch.measured);
    const Eigen::Vector2d mean_r = patch.sum_centre / n - (M * (patch.sum_seen / n) + t);
    sum2 += mean_r.squaredNorm();
  }
  result.ortho_pixel_error_m = MetricValue::of(std::sqrt(sum2 / patches_measured));
  return result;
}

OrthoPixelError measureRunOrthoPixelError(const std::filesystem::path& ortho_hdr,
                                          const std::filesystem::path& ancillary_hdr,
                                          const std::vector<SE3d>& T_W_U_true,
                                          const PushbroomCamera& camera_true,
                                          const MeshRayCaster& true_scene,
                                          const GeodeticPoint& origin,
                                          const OrthoPixelErrorOptions& options) {
  std::error_code error;
  const auto bothMissing = [](const std::string& why) {
    OrthoPixelError result;
    result.ortho_pixel_error_m = result.ortho_pixel_error_abs_m = MetricValue::missing(why);
    return result;
  };
  if (!std::filesystem::is_regular_file(ortho_hdr, error)) return bothMissing(kNoOrthoImage);
  if (!std::filesystem::is_regular_file(ancillary_hdr, error)) return bothMissing(kNoAncillaryLayer);
  const EnviHeader ortho = readEnviHeader(ortho_hdr);
  const EnviHeader ancillary = readEnviHeader(ancillary_hdr);
  if (ancillary.lines != ortho.lines || ancillary.samples != ortho.samples ||
      ancillary.map_info != ortho.map_info) {
    throw InputError(ancillary_hdr, "",
                     "not on the grid of " + ortho_hdr.string() + " (" + std::to_string(ancillary.lines) +
                         " x " + std::to_string(ancillary.samples) + " pixels against " +
                         std::to_string(ortho.lines) + " x " + std::to_string(ortho.samples) +
                         ", or another map info): expected the ortho-image's ancillary layer");
  }
  return measureOrthoPixelError(ancillary_hdr, T_W_U_true, camera_true, true_scene, origin, options);
}

}  // namespace hsmap
