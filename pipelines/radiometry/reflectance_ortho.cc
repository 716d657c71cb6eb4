#include "pipelines/radiometry/reflectance_ortho.h"

#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "core/io/envi_reader.h"
#include "core/io/envi_writer.h"
#include "pipelines/radiometry/lamp_geometry.h"

namespace hsmap {

namespace fs = std::filesystem;

std::string ReflectanceReport::summary() const {
  std::ostringstream text;
  text << "reflectance: " << valid << " of " << pixels << " pixels (" << empty << " empty in the radiance ortho, "
       << shadowed << " NaN in a lamp's shadow, " << undetermined
       << " NaN undetermined: no hit, no lamp facing it, a depth edge or every band too dark); " << dark_band_values
       << " band values NaN in valid pixels (the lamps' signal below the sensor's noise) in " << seconds << " s\n";
  return text.str();
}

namespace {

enum class PixelFate : std::uint8_t { valid, empty, shadowed, undetermined };

}  // namespace

ReflectanceReport writeReflectanceOrtho(const fs::path& folder, const PushbroomCamera& camera,
                                        const std::vector<LinePose>& line_poses, const MeshRayCaster& mesh,
                                        const LightsConfig& lights, const SE3d& T_C_U,
                                        const std::vector<double>& response_dn, const WaterEstimate& water,
                                        const ReflectanceOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const EnviReader ortho(folder / "ortho.hdr");
  const EnviReader ancillary(folder / "ancillary.hdr");
  const int rows = ortho.lines(), cols = ortho.samples(), bands = ortho.bands();
  if (ancillary.lines() != rows || ancillary.samples() != cols || ancillary.bands() != 4) {
    throw std::invalid_argument("reflectance: " + (folder / "ancillary.hdr").string() +
                                " is not the 4-band companion of ortho.hdr's grid");
  }
  if (int(response_dn.size()) != bands || water.bands() != bands) {
    throw std::invalid_argument("reflectance: the ortho has " + std::to_string(bands) + " bands, the lamp response " +
                                std::to_string(response_dn.size()) + " and the water estimate " +
                                std::to_string(water.bands()));
  }
  std::unordered_map<long long, std::size_t> pose_of_line;
  for (std::size_t i = 0; i < line_poses.size(); ++i) pose_of_line.emplace(line_poses[i].line, i);

  ReflectanceReport report;
  report.pixels = std::int64_t(rows) * cols;
  report.hdr = folder / "reflectance.hdr";
  EnviHeader header = ortho.header();
  header.description = "hsmap reflectance: the seabed's reflectance (0..1), radiance corrected for the lamps, "
                       "the beam and the water (docs/RADIOMETRY.md); NaN where empty, shadowed or undetermined";
  header.interleave = EnviInterleave::bil;
  {
    EnviWriter writer(report.hdr, header);
    std::vector<float> dn(std::size_t(bands) * std::size_t(cols)), anc(std::size_t(4) * std::size_t(cols));
    std::vector<float> out(dn.size());
    std::vector<PixelFate> fate(static_cast<std::size_t>(cols), PixelFate::empty);
    std::vector<int> dark_values(static_cast<std::size_t>(cols), 0);
    constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
    for (int row = 0; row < rows; ++row) {
      ortho.readLine(row, dn.data());
      ancillary.readLine(row, anc.data());
      tbb::parallel_for(0, cols, [&](int col) {
        auto fail = [&](PixelFate why) {
          for (int b = 0; b < bands; ++b) out[std::size_t(b) * std::size_t(cols) + std::size_t(col)] = kNaN;
          fate[std::size_t(col)] = why;
        };
        if (!std::isfinite(dn[std::size_t(col)])) return fail(PixelFate::empty);
        const float line_f = anc[std::size_t(col)], sample_f = anc[std::size_t(cols) + std::size_t(col)];
        if (!std::isfinite(line_f) || !std::isfinite(sample_f)) return fail(PixelFate::undetermined);
        const auto pose = pose_of_line.find(std::lround(line_f));
        if (pose == pose_of_line.end()) return fail(PixelFate::undetermined);
        const SE3d& T_W_U = line_poses[pose->second].T;
        const auto ray_U = camera.unproject(double(sample_f));
        if (!ray_U) return fail(PixelFate::undetermined);
        Ray ray;
        ray.origin = T_W_U.t;
        ray.direction = T_W_U.rotationMatrix() * ray_U->normalized();
        ray.t_near = options.cast.min_range_m;
        ray.t_far = options.cast.max_range_m;
        const RayHit hit = mesh.intersect(ray);
        if (!hit.hit()) return fail(PixelFate::undetermined);
        // A gap-filled pixel at a depth edge blends hits of two surfaces: its
        // interpolated range then differs from the recast one, and neither
        // surface's geometry is the pixel's.
        const float range_f = anc[2 * std::size_t(cols) + std::size_t(col)];
        if (std::isfinite(range_f) &&
            std::abs(hit.distance - double(range_f)) > options.max_range_mismatch * hit.distance) {
          return fail(PixelFate::undetermined);
        }
        const Eigen::Vector3d p_W = ray.origin + hit.distance * ray.direction;
        const LampPathsAtPoint paths =
            lampPathsAt(lampsInWorld(lights, T_W_U, T_C_U), p_W, hit.normal, T_W_U.t, &mesh);
        if (paths.shadowed > 0) return fail(PixelFate::shadowed);
        if (paths.lit.empty()) return fail(PixelFate::undetermined);
        int dark = 0;
        for (int b = 0; b < bands; ++b) {
          const double illumination =
              lampIllumination(paths.lit, hit.distance, water.attenuation_per_m[std::size_t(b)], water.beam.data());
          const double signal = response_dn[std::size_t(b)] * illumination;
          const std::size_t i = std::size_t(b) * std::size_t(cols) + std::size_t(col);
          if (!(signal >= options.min_signal_dn)) {
            out[i] = kNaN;
            ++dark;
            continue;
          }
          out[i] = float((double(dn[i]) - water.backscatter_dn[std::size_t(b)]) / signal);
        }
        dark_values[std::size_t(col)] = dark;
        fate[std::size_t(col)] = dark == bands ? PixelFate::undetermined : PixelFate::valid;
      });
      for (std::size_t c = 0; c < fate.size(); ++c) {
        if (fate[c] == PixelFate::valid) report.dark_band_values += dark_values[c];
        dark_values[c] = 0;
      }
      for (PixelFate f : fate) {
        switch (f) {
          case PixelFate::valid: ++report.valid; break;
          case PixelFate::empty: ++report.empty; break;
          case PixelFate::shadowed: ++report.shadowed; break;
          case PixelFate::undetermined: ++report.undetermined; break;
        }
      }
      writer.writeLine(out.data());
    }
    writer.finish();
  }
  if (options.write_geotiff) {
    report.tif = folder / "reflectance.tif";
    exportEnviToCog(report.hdr, report.tif, options.geotiff);
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace hsmap
