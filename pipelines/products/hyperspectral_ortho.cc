#include "pipelines/products/hyperspectral_ortho.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <future>
#include <limits>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "core/io/envi_ignore_value.h"
#include "core/io/envi_writer.h"
#include "core/io/ply_io.h"
#include "core/util/free_space.h"
#include "core/util/input_error.h"
#include "core/util/median.h"
#include "core/util/message_text.h"
#include "core/util/progress.h"
#include "core/util/stage_timer.h"
#include "pipelines/products/ortho_accumulator.h"
#include "pipelines/products/ortho_quicklook.h"
#include "pipelines/products/product_headers.h"
#include "pipelines/products/spectrum_validity.h"
#include "pipelines/products/w_to_utm_lattice.h"

namespace hsmap {

namespace {

using Clock = std::chrono::steady_clock;
void require(bool ok, const std::string& field, const std::string& expected) {
  if (!ok) throw std::invalid_argument("hyperspectral options: " + field + ": expected " + expected);
}

// The local spacing of the scan lines (ortho gap filling, OrthoHit::reach_px).
// A point p_W seen by a line's pixel is seen by the same pixel of a
// neighbouring line (the previous or next cube line, when posed) at
// T_other * T_self^-1 * p_W: carried with the UHI. Its horizontal
// displacement (A p_W + t, A = R - I) is the lines' own spacing at that
// pixel (wider on the outer side of a turn), not the surface's: a step of
// the seabed between two lines' hits (an occluded shadow) does not widen
// it. A line with no posed neighbour has no motion (a gap in the lines is
// not filled across).
struct LineMotion {
  Eigen::Matrix3d A;
  Eigen::Vector3d t;
};
std::vector<LineMotion> neighbourMotions(const std::vector<LinePose>& line_poses, std::size_t pose) {
  std::vector<LineMotion> motions;
  const LinePose& self = line_poses[pose];
  const SE3d T_U_W = self.T.inverse();
  for (const std::size_t other : {pose - 1, pose + 1}) {
    if (other >= line_poses.size() || std::llabs(line_poses[other].line - self.line) != 1) continue;
    const SE3d moved = line_poses[other].T * T_U_W;
    motions.push_back({moved.q.toRotationMatrix() - Eigen::Matrix3d::Identity(), moved.t});
  }
  return motions;
}
// The first and last samples of a line that hit the surface; nullopt when none does.
std::optional<std::pair<int, int>> hitSampleRange(const ScanLineHits& hits) {
  const int samples = int(hits.p_W.size());
  int first = 0, last = samples - 1;
  while (first < samples && !hits.hit(first)) ++first;
  while (last >= first && !hits.hit(last)) --last;
  if (first > last) return std::nullopt;
  return std::make_pair(first, last);
}
double lineSpacingAt(const std::vector<LineMotion>& motions, const Eigen::Vector3d& p_W) {
  double spacing = 0.0;
  for (const LineMotion& m : motions) spacing = std::max(spacing, (m.A * p_W + m.t).head<2>().norm());
  return spacing;
}
// The line's largest spacing (metres): at its first, middle and last hits
// (the displacement is affine in the point, so along a line of hits it is
// largest at an end or, over relief, near them); 0 without hits.
double lineSpacingM(const std::vector<LinePose>& line_poses, std::size_t pose, const ScanLineHits& hits) {
  const std::optional<std::pair<int, int>> range = hitSampleRange(hits);
  if (!range) return 0.0;
  const auto [first, last] = *range;
  // A hit at or after the line's centre (last is one, so the walk stops there).
  int middle = std::clamp(int(hits.p_W.size()) / 2, first, last);
  while (!hits.hit(middle)) ++middle;
  const std::vector<LineMotion> motions = neighbourMotions(line_poses, pose);
  return std::max({lineSpacingAt(motions, hits.p_W[std::size_t(first)]),
                   lineSpacingAt(motions, hits.p_W[std::size_t(middle)]),
                   lineSpacingAt(motions, hits.p_W[std::size_t(last)])});
}
// Each hit's reach (grid pixels): its line's spacing at its pixel, 0 for
// the hits less than `edge_m` (on the ground) from the line's first or last
// hit: the filling's surround test lets a run of sources fill up to about
// reach / sqrt(2) beyond a straight edge of the swath, so near the swath's
// sides only the median spacing's radius applies.
void hitReachPx(const std::vector<LinePose>& line_poses, std::size_t pose, const ScanLineHits& hits,
                double pixel_m, double edge_m, std::vector<float>& reach_px) {
  std::fill(reach_px.begin(), reach_px.end(), 0.0f);
  const std::optional<std::pair<int, int>> range = hitSampleRange(hits);
  if (!range) return;
  auto [first, last] = *range;
  const Eigen::Vector2d first_NE = hits.p_W[std::size_t(first)].head<2>();
  const Eigen::Vector2d last_NE = hits.p_W[std::size_t(last)].head<2>();
  auto farFromEnds = [&](int s) {
    const Eigen::Vector2d p = hits.p_W[std::size_t(s)].head<2>();
    return (p - first_NE).norm() >= edge_m && (p - last_NE).norm() >= edge_m;
  };
  while (first <= last && !(hits.hit(first) && farFromEnds(first))) ++first;
  while (last >= first && !(hits.hit(last) && farFromEnds(last))) --last;
  const std::vector<LineMotion> motions = neighbourMotions(line_poses, pose);
  for (int s = first; s <= last; ++s) {
    if (!hits.hit(s)) continue;
    reach_px[std::size_t(s)] = float(lineSpacingAt(motions, hits.p_W[std::size_t(s)]) / pixel_m);
  }
}

// What the footprint pass keeps of a line.
struct LineFootprint {
  std::size_t pose = 0;            // index into line_poses
  double spacing_m = 0.0;          // lineSpacingM: to its neighbouring lines, at most
  Eigen::AlignedBox3d box_W;       // of its hits
  int row_min = 0, row_max = -1;   // grid rows its hits can fall in
};

EnviHeader orthoHeader(const EnviReader& cube, const std::vector<double>& wavelengths_nm,
                       const OrthoGrid& grid, EnviInterleave interleave) {
  EnviHeader header = spectralProductHeader(cube, wavelengths_nm, grid.rows, grid.cols, interleave);
  header.map_info = grid.mapInfo();
  header.description =
      "hsmap products: hyperspectral ortho-image (mean of the UHI spectra whose ray hit each "
      "pixel, gaps filled within the line spacing), values as in the cube, NaN where nothing was seen";
  return header;
}

EnviHeader ancillaryHeader(const OrthoGrid& grid) {
  EnviHeader header = ancillaryProductHeader(grid.rows, grid.cols);
  header.map_info = grid.mapInfo();
  header.description =
      "hsmap products: per ortho pixel, scan line, sample, range and incidence angle of the hit "
      "nearest the pixel centre (gap-filled pixels: of the nearest observed pixel); NaN where empty";
  return header;
}

}  // namespace

void HyperspectralOptions::validate() const {
  require(pixel_m > 0.0 && std::isfinite(pixel_m), "pixel_m", "a pixel size > 0 m");
  require(fill_radius_px >= -1, "fill_radius_px", "-1 (automatic), 0 (none) or a radius in pixels");
  require(max_fill_radius_px >= 0, "max_fill_radius_px", "a radius >= 0 pixels");
  require(tile_memory_mb >= 1.0 && std::isfinite(tile_memory_mb), "tile_memory_mb", "at least 1 MB");
  require(lines_per_batch >= 1, "lines_per_batch", "at least 1");
  require(quicklook_max_side >= 16, "quicklook_max_side", "at least 16 pixels");
  cast.validate();
  if (write_geotiff) geotiff.validate();
}

double HyperspectralReport::coverage() const {
  const std::int64_t pixels = grid.pixelCount();
  return pixels > 0 ? double(validPixels()) / double(pixels) : 0.0;
}

std::string HyperspectralReport::summary() const {
  std::ostringstream out;
  out << "hyperspectral ortho-image: " << grid.cols << " x " << grid.rows << " pixels of "
      << grid.pixel_m * 1000.0 << " mm, " << bands << " bands, UTM zone " << grid.zone
      << (grid.northern ? "N" : "S") << ", " << tiles << " tile(s) of " << tile_rows << " rows\n";
  out << "  scan lines: " << lines << " cast, " << lines_with_hits << " with hits, " << lines_read
      << " cube lines read\n";
  out << "  rays: " << pixels_cast << " cast, " << hits << " hits, " << misses << " misses";
  if (pixels_without_ray > 0) out << ", " << pixels_without_ray << " pixels without a ray";
  out << "\n  spectra: " << painted << " painted, " << skipped_non_finite << " skipped (NaN/inf), "
      << skipped_ignore_value << " skipped (data ignore value)\n";
  out << "  pixels: " << observed_pixels << " observed + " << filled_pixels << " gap-filled (radius "
      << fill_radius_px << " px; line spacing " << line_spacing_m * 1000.0 << " mm, sample spacing "
      << sample_spacing_m * 1000.0 << " mm) = " << coverage() * 100.0 << " % of the grid\n";
  out << "  time:";
  for (const auto& [name, s] : seconds) out << " " << name << " " << s << " s;";
  out << " peak memory " << peak_memory_mb << " MB (" << peak_memory_before_geotiff_mb
      << " MB before the GeoTIFF)\n";
  return out.str();
}

HyperspectralReport writeHyperspectralOrtho(const EnviReader& cube,
                                            const std::vector<double>& wavelengths_nm,
                                            const PushbroomCamera& camera,
                                            const std::vector<LinePose>& line_poses,
                                            const MeshRayCaster& mesh,
                                            const UtmProjection& projection,
                                            const std::filesystem::path& out_folder,
                                            const HyperspectralOptions& options, std::ostream& log) {
  options.validate();
  const int bands = cube.bands();
  const int samples = cube.samples();
  requireCubeMatches("writeHyperspectralOrtho", cube, wavelengths_nm, camera);
  for (const LinePose& pose : line_poses) {
    if (pose.line < 0 || pose.line >= cube.lines()) {
      throw std::invalid_argument("writeHyperspectralOrtho: line pose for scan line " +
                                  std::to_string(pose.line) + ", the cube has " +
                                  std::to_string(cube.lines()) + " lines");
    }
  }
  const std::optional<float> ignore = enviDataIgnoreValue(cube.header(), cube.headerPath());
  StageTimings timings;
  HyperspectralReport report;
  report.bands = bands;
  report.lines = std::int64_t(line_poses.size());
  const ScanLineCaster caster(camera, mesh, options.cast);
  const std::size_t batch = std::size_t(options.lines_per_batch);

  // ---- 1. footprint pass -----------------------------------------------------
  std::vector<LineFootprint> footprints;
  Eigen::AlignedBox2d box_NE;
  double down_sum = 0.0;
  std::int64_t down_count = 0;
  {
    auto stage = timings.stage("footprint cast");
    const int mid = samples / 2;
    const int next = std::min(samples - 1, mid + 1);
    std::vector<double> line_steps, sample_steps;
    Eigen::Vector3d previous_centre = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
    std::vector<ScanLineHits> hits;
    std::vector<std::int64_t> lines;
    std::vector<SE3d> poses;
    Progress progress("hyperspectral footprint", std::int64_t(line_poses.size()), "lines", log);
    for (std::size_t first = 0; first < line_poses.size(); first += batch) {
      const std::size_t count = std::min(batch, line_poses.size() - first);
      lines.clear();
      poses.clear();
      for (std::size_t k = 0; k < count; ++k) {
        lines.push_back(line_poses[first + k].line);
        poses.push_back(line_poses[first + k].T);
      }
      caster.castLines(lines, poses, hits);
      for (std::size_t k = 0; k < count; ++k) {
        const ScanLineHits& line = hits[k];
        report.pixels_cast += line.hits + line.misses;
        report.pixels_without_ray += line.no_ray;
        report.hits += line.hits;
        report.misses += line.misses;
        const Eigen::Vector3d centre = line.p_W[std::size_t(mid)];
        if (line.hit(mid) && previous_centre.allFinite()) {
          line_steps.push_back((centre - previous_centre).head<2>().norm());
        }
        previous_centre = centre;
        if (line.hit(mid) && line.hit(next) && next != mid) {
          sample_steps.push_back((line.p_W[std::size_t(next)] - centre).head<2>().norm());
        }
        if (line.hits == 0) continue;
        LineFootprint footprint;
        footprint.pose = first + k;
        footprint.spacing_m = lineSpacingM(line_poses, first + k, line);
        for (int s = 0; s < samples; ++s) {
          if (!line.hit(s)) continue;
          footprint.box_W.extend(line.p_W[std::size_t(s)]);
          down_sum += line.p_W[std::size_t(s)].z();
          ++down_count;
        }
        box_NE.extend(footprint.box_W.min().head<2>());
        box_NE.extend(footprint.box_W.max().head<2>());
        footprints.push_back(footprint);
      }
      progress.advance(std::int64_t(count));
    }
    progress.finish();
    report.lines_with_hits = std::int64_t(footprints.size());
    report.line_spacing_m = upperMedian(line_steps);
    report.sample_spacing_m = upperMedian(sample_steps);
  }
  if (footprints.empty()) {
    throw std::runtime_error("hyperspectral ortho-image: none of the " +
                             std::to_string(line_poses.size()) +
                             " scan lines' rays hit the mesh (wrong poses or mesh?)");
  }

  // ---- 2. grid ---------------------------------------------------------------
  const WToUtmLattice lattice(projection, box_NE, down_sum / double(down_count));
  Eigen::AlignedBox2d box_EN;
  std::vector<Eigen::AlignedBox2d> line_boxes_EN(footprints.size());
  for (std::size_t i = 0; i < footprints.size(); ++i) {
    const Eigen::AlignedBox3d& b = footprints[i].box_W;
    Eigen::AlignedBox2d en;
    for (int corner = 0; corner < 8; ++corner) {
      en.extend(lattice.toUtm(b.corner(Eigen::AlignedBox3d::CornerType(corner))));
    }
    // The map is affine in (north, east, down) to ~1e-7 m over a survey: a
    // millimetre of margin keeps every hit of the line inside its box.
    en.min().array() -= 1e-3;
    en.max().array() += 1e-3;
    line_boxes_EN[i] = en;
    box_EN.extend(en);
  }
  const OrthoGrid grid =
      OrthoGrid::coveringUtm(box_EN, options.pixel_m, projection.zone(), projection.northernHemisphere());
  report.grid = grid;
  for (std::size_t i = 0; i < footprints.size(); ++i) {
    footprints[i].row_min = std::max(0, grid.containingPixel(line_boxes_EN[i].max()).y());
    footprints[i].row_max = std::min(grid.rows - 1, grid.containingPixel(line_boxes_EN[i].min()).y());
  }
  const double spacing = std::max(report.line_spacing_m, report.sample_spacing_m);
  report.fill_radius_px =
      options.fill_radius_px >= 0
          ? options.fill_radius_px
          : std::min(options.max_fill_radius_px, int(std::ceil(spacing / options.pixel_m - 1e-9)));
  // Automatic filling also follows the lines' local spacing (each hit's
  // reach, up to max_fill_radius_px): the halo covers the largest reach.
  const bool local_reach = options.fill_radius_px < 0;
  double widest_spacing_m = 0.0;
  for (const LineFootprint& f : footprints) widest_spacing_m = std::max(widest_spacing_m, f.spacing_m);
  const int halo =
      local_reach ? std::clamp(int(std::ceil(widest_spacing_m / options.pixel_m - 1e-9)),
                               report.fill_radius_px, std::max(report.fill_radius_px, options.max_fill_radius_px))
                  : report.fill_radius_px;
  const std::int64_t row_bytes = OrthoTileAccumulator::bytesPerRow(grid.cols, bands);
  const std::int64_t budget_rows = std::int64_t(options.tile_memory_mb * 1024.0 * 1024.0) / row_bytes;
  report.tile_rows = int(std::clamp<std::int64_t>(budget_rows - 2 * halo, 1, grid.rows));
  report.tiles = (grid.rows + report.tile_rows - 1) / report.tile_rows;
  log << "hyperspectral ortho-image: " << grid.cols << " x " << grid.rows << " pixels of "
      << grid.pixel_m * 1000.0 << " mm in " << report.tiles << " tile(s) of " << report.tile_rows
      << " rows; gap-fill radius " << report.fill_radius_px << " px"
      << (local_reach ? " (up to " + std::to_string(halo) + " px where the lines fan out)" : std::string())
      << "\n";

  // ---- 3. tiles ----------------------------------------------------------------
  std::filesystem::create_directories(out_folder);
  {
    // The ENVI ortho-image (4 bytes a value) and its ancillary layers (16
    // bytes a pixel), before hours of casting can end on a full disk.
    const std::uint64_t pixels = std::uint64_t(grid.rows) * std::uint64_t(grid.cols);
    requireFreeSpace(out_folder, pixels * (std::uint64_t(bands) * 4 + 16),
                     "hyperspectral ortho-image (" + std::to_string(grid.cols) + " x " + std::to_string(grid.rows) +
                         " pixels of " + fixedDecimals(grid.pixel_m * 1000.0, 1) + " mm, " + std::to_string(bands) +
                         " bands; a larger --ortho-pixel shrinks it by its square)");
  }
  if (options.on_grid) options.on_grid(grid);
  report.ortho_hdr = out_folder / "ortho.hdr";
  report.ancillary_hdr = out_folder / "ancillary.hdr";
  {
    auto stage = timings.stage("ortho tiles");
    // O_DIRECT: the ortho is GBs that nobody reads back soon; through the
    // page cache it was written at a sixth of the speed and evicted the cube.
    EnviWriter ortho_writer(report.ortho_hdr, orthoHeader(cube, wavelengths_nm, grid, options.interleave),
                            EnviWriteMode::direct);
    EnviWriter ancillary_writer(report.ancillary_hdr, ancillaryHeader(grid), EnviWriteMode::direct);
    std::optional<OrthoQuicklook> quicklook;
    if (options.write_quicklook) {
      quicklook.emplace(grid.rows, grid.cols, nearestRgbBands(wavelengths_nm), options.quicklook_max_side);
    }
    std::int64_t total_reads = 0;
    for (int t = 0; t < report.tiles; ++t) {
      const int row_begin = t * report.tile_rows;
      const int row_end = std::min(grid.rows, row_begin + report.tile_rows);
      for (const LineFootprint& f : footprints) {
        if (f.row_max >= row_begin - halo && f.row_min < row_end + halo) ++total_reads;
      }
    }
    Progress progress("hyperspectral ortho", total_reads, "lines", log);
    double read_s = 0.0, cast_s = 0.0, prepare_s = 0.0, accumulate_s = 0.0, write_s = 0.0, allocate_s = 0.0;
    const std::size_t line_values = std::size_t(bands) * std::size_t(samples);
    // The buffers of one batch. Two slots: while batch i is accumulated
    // (sequential) from one, batch i + 1 is read, cast and prepared into the
    // other (pipelined, see below).
    struct BatchSlot {
      std::vector<std::vector<float>> sample_major;  // lines read pixel-major
      std::vector<std::vector<Eigen::Vector2d>> col_row;
      // Per sample: 0 no hit, 1 valid, 2 non-finite, 3 ignore value.
      std::vector<std::vector<std::uint8_t>> status, non_finite, ignored;
      std::vector<std::vector<float>> reach_px;  // per sample (OrthoHit::reach_px)
      std::vector<std::size_t> footprint;        // into footprints
      std::vector<ScanLineHits> hits;
      std::vector<std::int64_t> lines;
      std::vector<SE3d> poses;
      std::size_t count = 0;
    };
    BatchSlot slots[2];
    for (BatchSlot& slot : slots) {
      slot.sample_major.assign(batch, std::vector<float>(line_values));
      slot.col_row.assign(batch, std::vector<Eigen::Vector2d>(std::size_t(samples)));
      slot.status.assign(batch, std::vector<std::uint8_t>(std::size_t(samples)));
      slot.non_finite.assign(batch, std::vector<std::uint8_t>(std::size_t(samples)));
      slot.ignored.assign(batch, std::vector<std::uint8_t>(std::size_t(samples)));
      slot.reach_px.assign(batch, std::vector<float>(std::size_t(samples), 0.0f));
    }
    std::vector<float> ancillary_out(std::size_t(4) * grid.cols);
    // Two accumulators, each reset for every other tile (their memory is
    // mapped once): while one tile is cast and accumulated, the previous one
    // is written by `writing` (the ENVI write of a 5 mm ortho, ~1 KB a pixel,
    // is the stage's floor on a disk of a few hundred MB/s).
    std::optional<OrthoTileAccumulator> accumulators[2];
    double write_wait_s = 0.0;
    std::future<double> writing;  // seconds the write took; declared after what it uses
    auto waitForWriting = [&] {
      if (!writing.valid()) return;
      const auto start = Clock::now();
      write_s += writing.get();
      write_wait_s += secondsSince(start);
    };
    for (int t = 0; t < report.tiles; ++t) {
      const int row_begin = t * report.tile_rows;
      const int row_end = std::min(grid.rows, row_begin + report.tile_rows);
      auto allocate_start = Clock::now();
      std::optional<OrthoTileAccumulator>& accumulator = accumulators[t % 2];
      if (!accumulator) {
        accumulator.emplace(grid, bands, row_begin, row_end, halo);
      } else {
        accumulator->reset(row_begin, row_end);  // its write (tile t - 2) was waited for
      }
      OrthoTileAccumulator& tile = *accumulator;
      allocate_s += secondsSince(allocate_start);
      std::vector<std::size_t> tile_lines;  // indices into footprints, in cube line order
      for (std::size_t i = 0; i < footprints.size(); ++i) {
        if (footprints[i].row_max >= tile.firstRow() && footprints[i].row_min < tile.lastRow()) {
          tile_lines.push_back(i);
        }
      }
      std::sort(tile_lines.begin(), tile_lines.end(), [&](std::size_t a, std::size_t b) {
        return line_poses[footprints[a].pose].line < line_poses[footprints[b].pose].line;
      });
      // Reads, casts and prepares the batch of tile_lines from `first` into `slot`.
      auto prepareBatch = [&](BatchSlot& slot, std::size_t first) {
        const std::size_t count = slot.count = std::min(batch, tile_lines.size() - first);
        slot.lines.clear();
        slot.poses.clear();
        slot.footprint.clear();
        for (std::size_t k = 0; k < count; ++k) {
          slot.footprint.push_back(tile_lines[first + k]);
          const LinePose& pose = line_poses[footprints[slot.footprint.back()].pose];
          slot.lines.push_back(pose.line);
          slot.poses.push_back(pose.T);
        }
        // Reading (one reader: sequential) overlaps casting (parallel).
        tbb::parallel_invoke(
            [&] {
              const auto start = Clock::now();
              for (std::size_t k = 0; k < count; ++k) {
                cube.readLinePixelMajor(int(slot.lines[k]), slot.sample_major[k].data());
              }
              read_s += secondsSince(start);
            },
            [&] {
              const auto start = Clock::now();
              caster.castLines(slot.lines, slot.poses, slot.hits);
              cast_s += secondsSince(start);
            });
        const auto start = Clock::now();
        tbb::parallel_for(std::size_t(0), count, [&](std::size_t k) {
          const float* in = slot.sample_major[k].data();
          std::uint8_t* non_finite = slot.non_finite[k].data();
          std::uint8_t* ignored = slot.ignored[k].data();
          markInvalidSamples(in, bands, samples, cube.header().data_type, ignore, non_finite, ignored);
          const ScanLineHits& line = slot.hits[k];
          for (int s = 0; s < samples; ++s) {
            std::uint8_t& st = slot.status[k][std::size_t(s)];
            if (!line.hit(s)) {
              st = 0;
              continue;
            }
            slot.col_row[k][std::size_t(s)] = grid.pixelOfUtm(lattice.toUtm(line.p_W[std::size_t(s)]));
            st = non_finite[s] != 0 ? 2 : ignored[s] != 0 ? 3 : 1;
          }
          // Only a line whose spacing exceeds the median radius somewhere
          // needs each hit's reach (on a straight survey, few do).
          const LineFootprint& footprint = footprints[slot.footprint[k]];
          if (local_reach && footprint.spacing_m > report.fill_radius_px * grid.pixel_m) {
            hitReachPx(line_poses, footprint.pose, line, grid.pixel_m, halo * grid.pixel_m,
                       slot.reach_px[k]);
          } else {
            std::fill(slot.reach_px[k].begin(), slot.reach_px[k].end(), 0.0f);
          }
        });
        prepare_s += secondsSince(start);
      };
      // Adds a prepared batch to the tile, lines in cube order (the sums'
      // order, hence their bits, is that of a sequential loop).
      auto accumulateBatch = [&](const BatchSlot& slot) {
        const auto start = Clock::now();
        for (std::size_t k = 0; k < slot.count; ++k) {
          const ScanLineHits& line = slot.hits[k];
          OrthoHit hit;
          hit.line = float(line.line);
          for (int s = 0; s < samples; ++s) {
            const std::uint8_t st = slot.status[k][std::size_t(s)];
            if (st == 0) continue;
            const Eigen::Vector2d& p = slot.col_row[k][std::size_t(s)];
            if (st != 1) {
              if (tile.owns(p)) (st == 2 ? report.skipped_non_finite : report.skipped_ignore_value) += 1;
              continue;
            }
            hit.col_row = p;
            hit.spectrum = slot.sample_major[k].data() + std::size_t(s) * bands;
            hit.sample = float(s);
            hit.range_m = line.range_m[std::size_t(s)];
            hit.incidence_deg = line.incidence_deg[std::size_t(s)];
            hit.reach_px = slot.reach_px[k][std::size_t(s)];
            if (tile.add(hit)) ++report.painted;
          }
        }
        accumulate_s += secondsSince(start);
        report.lines_read += std::int64_t(slot.count);
        progress.advance(std::int64_t(slot.count));
      };
      // Pipeline: batch i is accumulated while batch i + 1 is prepared.
      const std::size_t batches = (tile_lines.size() + batch - 1) / batch;
      for (std::size_t i = 0; i < batches; ++i) {
        BatchSlot& next = slots[i % 2];
        if (i == 0) {
          prepareBatch(next, 0);
        } else {
          tbb::parallel_invoke([&] { prepareBatch(next, i * batch); },
                               [&] { accumulateBatch(slots[(i - 1) % 2]); });
        }
      }
      if (batches > 0) accumulateBatch(slots[(batches - 1) % 2]);
      const auto tile_start = Clock::now();
      tile.finish(report.fill_radius_px);
      accumulate_s += secondsSince(tile_start);
      report.observed_pixels += tile.observedPixels();
      report.filled_pixels += tile.filledPixels();
      // Rows go out in order: tile t - 1's write ends before tile t's starts.
      waitForWriting();
      writing = std::async(std::launch::async, [&, row_begin, row_end]() {
        const auto start = Clock::now();
        for (int row = row_begin; row < row_end; ++row) {
          // Straight into the writer's staging buffer where it can take the
          // floats (a copy of every byte of the ortho-image saved).
          ortho_writer.writeLineWith([&](float* line) {
            tile.spectraRow(row, line);
            if (quicklook) quicklook->addRow(row, line);
          });
          tile.ancillaryRow(row, ancillary_out.data());
          ancillary_writer.writeLine(ancillary_out.data());
        }
        return secondsSince(start);
      });
    }
    waitForWriting();
    const auto start = Clock::now();
    ortho_writer.finish();
    ancillary_writer.finish();
    write_s += secondsSince(start);
    progress.finish();
    stage.stop();
    timings.record("  allocate + clear tiles", allocate_s);
    timings.record("  read cube (overlaps cast)", read_s);
    timings.record("  cast", cast_s);
    timings.record("  project + check", prepare_s);
    timings.record("  accumulate + fill (overlaps the next batch)", accumulate_s);
    timings.record("  write ENVI (overlaps the next tile)", write_s);
    timings.record("  wait for the write", write_wait_s);
    if (quicklook) {
      auto ql = timings.stage("quick-look");
      report.quicklook_png = out_folder / "ortho_rgb.png";
      quicklook->write(report.quicklook_png);
    }
  }

  report.peak_memory_before_geotiff_mb = peakResidentMemoryMb();

  // ---- 4. GeoTIFF ----------------------------------------------------------------
  if (options.write_geotiff) {
    auto stage = timings.stage("geotiff");
    report.ortho_tif = out_folder / "ortho.tif";
    exportEnviToCog(report.ortho_hdr, report.ortho_tif, options.geotiff);
  }
  report.seconds = timings.seconds();
  report.peak_memory_mb = peakResidentMemoryMb();
  return report;
}

PlyMesh readSurfaceMesh(const std::filesystem::path& mesh_ply) {
  PlyMesh ply = readPly(mesh_ply);
  if (ply.triangles.empty()) {
    throw InputError(mesh_ply, "", "expected a surface mesh (triangles), found a point cloud of " +
                                       std::to_string(ply.vertices.size()) + " vertices");
  }
  return ply;
}

HyperspectralReport writeHyperspectralProducts(const Survey& survey,
                                               const std::vector<LinePose>& line_poses,
                                               const std::filesystem::path& mesh_ply,
                                               const std::filesystem::path& out_folder,
                                               const HyperspectralOptions& options,
                                               std::ostream& log) {
  options.validate();
  if (!survey.cube) throw std::invalid_argument("writeHyperspectralProducts: the survey's cube is not open");
  const auto start = Clock::now();
  const PlyMesh ply = readSurfaceMesh(mesh_ply);
  const MeshRayCaster mesh(ply.vertices, ply.triangles);
  const double mesh_s = secondsSince(start);
  const PushbroomCamera camera(options.camera.value_or(survey.config.uhi.camera));
  const UtmProjection projection(survey.origin);
  HyperspectralReport report = writeHyperspectralOrtho(*survey.cube, survey.wavelengths_nm, camera,
                                                       line_poses, mesh, projection, out_folder,
                                                       options, log);
  report.seconds.insert(report.seconds.begin(), std::make_pair(std::string("read mesh + BVH"), mesh_s));
  return report;
}

}  // namespace hsmap
