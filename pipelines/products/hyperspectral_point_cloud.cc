#include "pipelines/products/hyperspectral_point_cloud.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "core/io/envi_ignore_value.h"
#include "pipelines/products/spectrum_validity.h"
#include "core/util/progress.h"
#include "core/util/stage_timer.h"
#include "pipelines/products/cell_release_map.h"
#include "pipelines/products/hyperspectral_point_cloud_ply.h"
#include "pipelines/products/spectral_cell_binner.h"

namespace hsmap {

namespace {

using Clock = std::chrono::steady_clock;

void require(bool ok, const std::string& field, const std::string& expected) {
  if (!ok) throw std::invalid_argument("hyperspectral point cloud options: " + field + ": expected " + expected);
}

// Per sample of a line: what becomes of it.
enum : std::uint8_t { kNoHit = 0, kValid = 1, kNonFinite = 2, kIgnored = 3 };

// One batch of lines: read, cast and checked while the previous one is binned.
struct BatchSlot {
  std::vector<std::vector<float>> sample_major;  // lines read pixel-major
  std::vector<std::vector<std::uint8_t>> status, non_finite, ignored;
  std::vector<ScanLineHits> hits;
  std::vector<std::int64_t> lines;
  std::vector<SE3d> poses;
  std::size_t first = 0, count = 0;  // sequences [first, first + count)
};

}  // namespace

void HyperspectralPointCloudOptions::validate() const {
  std::ostringstream range;
  range << "a cell size in [" << kMinCellM << ", " << kMaxCellM << "] m";
  require(cell_m >= kMinCellM && cell_m <= kMaxCellM, "cell_m", range.str());
  require(max_pending_mb >= 1.0 && std::isfinite(max_pending_mb), "max_pending_mb", "at least 1 MB");
  require(lines_per_batch >= 1, "lines_per_batch", "at least 1");
  cast.validate();
}

std::string HyperspectralPointCloudReport::summary() const {
  std::ostringstream out;
  out << "hyperspectral point cloud: " << points << " points in cubes of " << cell_m * 1000.0 << " mm, " << bands
      << " bands, " << double(bytes) / (1024.0 * 1024.0) << " MiB\n";
  out << "  scan lines: " << lines << " cast, " << lines_with_hits << " with hits; rays: " << hits << " hits, "
      << misses << " misses";
  if (pixels_without_ray > 0) out << ", " << pixels_without_ray << " pixels without a ray";
  out << "\n  spectra: " << binned << " binned (" << (points > 0 ? double(binned) / double(points) : 0.0)
      << " a point), " << skipped_non_finite << " skipped (NaN/inf), " << skipped_ignore_value
      << " skipped (data ignore value)\n";
  out << "  cells pending at most: " << peak_pending_cells << " (" << peak_pending_mb << " MB)";
  if (early_released > 0) out << "; " << early_released << " written early (survey back over its ground)";
  out << "\n  time:";
  for (const auto& [name, s] : seconds) out << " " << name << " " << s << " s;";
  out << "\n";
  return out.str();
}

HyperspectralPointCloudReport writeHyperspectralPointCloud(const EnviReader& cube,
                                                           const std::vector<double>& wavelengths_nm,
                                                           const PushbroomCamera& camera,
                                                           const std::vector<LinePose>& line_poses,
                                                           const MeshRayCaster& mesh, const GeodeticPoint& origin,
                                                           const std::filesystem::path& ply_path,
                                                           const HyperspectralPointCloudOptions& options,
                                                           std::ostream& log) {
  options.validate();
  const int bands = cube.bands();
  const int samples = cube.samples();
  requireCubeMatches("writeHyperspectralPointCloud", cube, wavelengths_nm, camera);
  for (const LinePose& pose : line_poses) {
    if (pose.line < 0 || pose.line >= cube.lines()) {
      throw std::invalid_argument("writeHyperspectralPointCloud: line pose for scan line " +
                                  std::to_string(pose.line) + ", the cube has " + std::to_string(cube.lines()) +
                                  " lines");
    }
  }
  const std::optional<float> ignore = enviDataIgnoreValue(cube.header(), cube.headerPath());
  HyperspectralPointCloudReport report;
  report.ply = ply_path;
  report.cell_m = options.cell_m;
  report.bands = bands;
  report.lines = std::int64_t(line_poses.size());
  StageTimings timings;
  const ScanLineCaster caster(camera, mesh, options.cast);
  const std::size_t batch = std::size_t(options.lines_per_batch);
  // Processing order: cube order (the cube streams forwards); sequence n is
  // line_poses[order[n]].
  std::vector<std::size_t> order(line_poses.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return line_poses[a].line < line_poses[b].line; });
  auto fillBatch = [&](BatchSlot& slot, std::size_t first) {
    slot.first = first;
    slot.count = std::min(batch, order.size() - first);
    slot.lines.clear();
    slot.poses.clear();
    for (std::size_t k = 0; k < slot.count; ++k) {
      slot.lines.push_back(line_poses[order[first + k]].line);
      slot.poses.push_back(line_poses[order[first + k]].T);
    }
  };

  // ---- 1. footprint: the (x, y) box of every line's hits ----------------------
  std::vector<Eigen::AlignedBox2d> boxes_xy(order.size());
  {
    auto stage = timings.stage("footprint cast");
    Progress progress("hyperspectral points: footprint", std::int64_t(order.size()), "lines", log);
    BatchSlot slot;
    for (std::size_t first = 0; first < order.size(); first += batch) {
      fillBatch(slot, first);
      caster.castLines(slot.lines, slot.poses, slot.hits);
      for (std::size_t k = 0; k < slot.count; ++k) {
        const ScanLineHits& line = slot.hits[k];
        report.hits += line.hits;
        report.misses += line.misses;
        report.pixels_without_ray += line.no_ray;
        report.lines_with_hits += line.hits > 0 ? 1 : 0;
        for (int s = 0; s < samples; ++s) {
          if (line.hit(s)) boxes_xy[first + k].extend(line.p_W[std::size_t(s)].head<2>());
        }
      }
      progress.advance(std::int64_t(slot.count));
    }
  }
  const CellReleaseMap releases(options.cell_m, boxes_xy);
  boxes_xy = {};

  // ---- 2. binning, written as the survey passes ---------------------------------
  std::filesystem::create_directories(ply_path.parent_path());
  HyperspectralPointCloudWriter writer(ply_path, wavelengths_nm, options.cell_m, origin);
  const auto max_pending_bytes = std::int64_t(options.max_pending_mb * 1024.0 * 1024.0);
  SpectralCellBinner binner(releases, bands, max_pending_bytes, [&](const CellPoint& p) { writer.write(p); });
  {
    auto stage = timings.stage("read + cast + bin");
    Progress progress("hyperspectral points", std::int64_t(order.size()), "lines", log);
    const std::size_t line_values = std::size_t(bands) * std::size_t(samples);
    BatchSlot slots[2];
    for (BatchSlot& slot : slots) {
      slot.sample_major.assign(batch, std::vector<float>(line_values));
      slot.status.assign(batch, std::vector<std::uint8_t>(std::size_t(samples)));
      slot.non_finite.assign(batch, std::vector<std::uint8_t>(std::size_t(samples)));
      slot.ignored.assign(batch, std::vector<std::uint8_t>(std::size_t(samples)));
    }
    double read_s = 0.0, cast_s = 0.0, check_s = 0.0, bin_s = 0.0;
    auto since = [](Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); };
    auto prepareBatch = [&](BatchSlot& slot, std::size_t first) {
      fillBatch(slot, first);
      tbb::parallel_invoke(
          [&] {
            const auto start = Clock::now();
            for (std::size_t k = 0; k < slot.count; ++k) cube.readLinePixelMajor(int(slot.lines[k]), slot.sample_major[k].data());
            read_s += since(start);
          },
          [&] {
            const auto start = Clock::now();
            caster.castLines(slot.lines, slot.poses, slot.hits);
            cast_s += since(start);
          });
      const auto start = Clock::now();
      tbb::parallel_for(std::size_t(0), slot.count, [&](std::size_t k) {
        const float* in = slot.sample_major[k].data();
        std::uint8_t* non_finite = slot.non_finite[k].data();
        std::uint8_t* ignored = slot.ignored[k].data();
        markInvalidSamples(in, bands, samples, cube.header().data_type, ignore, non_finite, ignored);
        const ScanLineHits& line = slot.hits[k];
        std::uint8_t* status = slot.status[k].data();
        for (int s = 0; s < samples; ++s) {
          status[s] = !line.hit(s) ? kNoHit : non_finite[s] != 0 ? kNonFinite : ignored[s] != 0 ? kIgnored : kValid;
        }
      });
      check_s += since(start);
    };
    // Sequential, in processing order: sums and output do not depend on threads.
    auto binBatch = [&](const BatchSlot& slot) {
      const auto start = Clock::now();
      for (std::size_t k = 0; k < slot.count; ++k) {
        const ScanLineHits& line = slot.hits[k];
        const std::uint8_t* status = slot.status[k].data();
        for (int s = 0; s < samples; ++s) {
          switch (status[s]) {
            case kValid:
              binner.add(line.p_W[std::size_t(s)], slot.sample_major[k].data() + std::size_t(s) * bands);
              ++report.binned;
              break;
            case kNonFinite: ++report.skipped_non_finite; break;
            case kIgnored: ++report.skipped_ignore_value; break;
            default: break;
          }
        }
        binner.releaseThrough(std::int64_t(slot.first + k));
      }
      bin_s += since(start);
      progress.advance(std::int64_t(slot.count));
    };
    const std::size_t batches = (order.size() + batch - 1) / batch;
    for (std::size_t i = 0; i < batches; ++i) {
      if (i == 0) {
        prepareBatch(slots[0], 0);
      } else {
        tbb::parallel_invoke([&] { prepareBatch(slots[i % 2], i * batch); },
                             [&] { binBatch(slots[(i - 1) % 2]); });
      }
    }
    if (batches > 0) binBatch(slots[(batches - 1) % 2]);
    binner.releaseAll();
    stage.stop();
    timings.record("  read cube (overlaps cast)", read_s);
    timings.record("  cast", cast_s);
    timings.record("  check spectra", check_s);
    timings.record("  bin + write points (overlaps the next batch)", bin_s);
  }
  {
    auto stage = timings.stage("write");
    writer.commit();
  }
  report.points = writer.points();
  report.bytes = writer.bytes();
  report.early_released = binner.earlyReleased();
  report.peak_pending_cells = binner.peakPendingCells();
  report.peak_pending_mb =
      double(binner.peakPendingCells()) * double(SpectralCellBinner::bytesPerCell(bands)) / (1024.0 * 1024.0);
  report.seconds = timings.seconds();
  return report;
}

}  // namespace hsmap
