#include "pipelines/calibration/strip_tie_points.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/geometry/pose_interpolation.h"
#include "core/io/envi_ignore_value.h"
#include "core/raycast/ray.h"
#include "core/util/input_error.h"
#include "core/util/median.h"
#include "core/util/message_text.h"
#include "pipelines/calibration/ortho_ncc.h"
#include "pipelines/products/scan_line_caster.h"
#include "pipelines/products/spectrum_validity.h"

namespace hsmap {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// The RGB frames as grey CV_32F images, decoded once each: the lines come
// in time order, so the nearest frame only moves forward and the last few
// decoded frames are all that is kept.
class GreyFrames {
 public:
  explicit GreyFrames(const RgbFrameSource& source) : source_(source) {}

  const cv::Mat& frame(int index) {
    for (const auto& [i, grey] : kept_) {
      if (i == index) return grey;
    }
    cv::Mat grey;
    try {
      cv::Mat grey8;
      cv::cvtColor(source_.frame(index), grey8, cv::COLOR_BGR2GRAY);
      grey8.convertTo(grey, CV_32F);
      ++decoded_;
    } catch (const InputError&) {
      // The front-end has reported it already; its lines predict nothing.
      ++undecodable_;
    }
    kept_.emplace_back(index, std::move(grey));
    if (kept_.size() > 3) kept_.pop_front();
    return kept_.back().second;
  }
  int decoded() const { return decoded_; }
  int undecodable() const { return undecodable_; }

 private:
  const RgbFrameSource& source_;
  std::deque<std::pair<int, cv::Mat>> kept_;
  int decoded_ = 0;
  int undecodable_ = 0;
};

// Bilinear value of a CV_32F image at (x, y), pixel centres at integers.
float bilinear(const cv::Mat& image, double x, double y) {
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const float ax = float(x - x0), ay = float(y - y0);
  const float* row0 = image.ptr<float>(y0);
  const float* row1 = image.ptr<float>(y0 + 1);
  return (1.0f - ay) * ((1.0f - ax) * row0[x0] + ax * row0[x0 + 1]) +
         ay * ((1.0f - ax) * row1[x0] + ax * row1[x0 + 1]);
}

// Index into `poses` of the posed frame nearest in time to t.
std::size_t nearestFrame(const std::vector<std::pair<int, SE3d>>& poses,
                         const RgbFrameSource& frames, double t) {
  const auto after = std::partition_point(poses.begin(), poses.end(), [&](const auto& pose) {
    return frames.time(pose.first) < t;
  });
  std::size_t k = std::size_t(after - poses.begin());
  if (k == poses.size()) return k - 1;
  if (k > 0 && t - frames.time(poses[k - 1].first) < frames.time(poses[k].first) - t) --k;
  return k;
}

// The posed lines at a continuous row (between rows i and i + 1: the pose
// interpolated, interpolatePose, as a line exposed between the two).
struct RowPose {
  SE3d T;
  double t = 0.0;
  double line_position = 0.0;  // cube line index, continuous
};
RowPose poseAt(const std::vector<LinePose>& lines, double row) {
  const int last = int(lines.size()) - 1;
  const int i = std::clamp(int(std::floor(row)), 0, std::max(0, last - 1));
  const double alpha = last == 0 ? 0.0 : std::clamp(row - i, 0.0, 1.0);
  const LinePose& a = lines[std::size_t(i)];
  const LinePose& b = lines[std::size_t(std::min(i + 1, last))];
  RowPose out;
  out.T = interpolatePose(a.T, b.T, alpha);
  out.t = (1.0 - alpha) * a.t + alpha * b.t;
  out.line_position = (1.0 - alpha) * double(a.line) + alpha * double(b.line);
  return out;
}

// One row of the real strip: the band combination of each sample (pixel
// major spectra), averaged over its column; NaN where a sample's spectrum
// is unusable (spectrum_validity.h).
void realStripRow(const float* pixel_major, const std::uint8_t* non_finite, const std::uint8_t* ignored,
                  int bands, int step, const std::vector<int>& used_bands,
                  const std::vector<double>& weights, double offset, int cols, float* row) {
  for (int c = 0; c < cols; ++c) {
    double sum = 0.0;
    bool usable = true;
    for (int s = c * step; s < (c + 1) * step && usable; ++s) {
      usable = non_finite[s] == 0 && ignored[s] == 0;
      double value = offset;
      const float* spectrum = pixel_major + std::size_t(s) * std::size_t(bands);
      for (const int b : used_bands) value += weights[std::size_t(b)] * spectrum[b];
      sum += value;
    }
    if (usable) row[c] = float(sum / step);
  }
}

// One row of the prediction: each column's hits seen by the grey frame
// posed at T_W_C, averaged; NaN where a sample misses the surface or falls
// outside the frame (margin_px inside). `hit_row` (optional) gets each
// column's mean hit.
void predictedStripRow(const ScanLineHits& hits, const SE3d& T_W_C, const cv::Mat& grey,
                       const PinholeRadtanCamera& camera, double margin_px, int step, int cols,
                       float* row, Eigen::Vector3f* hit_row) {
  const SE3d T_C_W = T_W_C.inverse();
  const double x_max = grey.cols - 1 - margin_px, y_max = grey.rows - 1 - margin_px;
  for (int c = 0; c < cols; ++c) {
    Eigen::Vector3d sum_W = Eigen::Vector3d::Zero();
    double sum_grey = 0.0;
    bool all_hit = true, all_seen = true;
    for (int s = c * step; s < (c + 1) * step && all_hit; ++s) {
      all_hit = hits.hit(s);
      if (!all_hit) break;
      const Eigen::Vector3d& p_W = hits.p_W[std::size_t(s)];
      sum_W += p_W;
      const Eigen::Vector3d p_C = T_C_W * p_W;
      if (!all_seen || p_C.z() <= 0.0) {
        all_seen = false;
        continue;
      }
      const Eigen::Vector2d uv = camera.project(p_C);
      if (!(uv.x() >= margin_px && uv.y() >= margin_px && uv.x() <= x_max && uv.y() <= y_max)) {
        all_seen = false;
        continue;
      }
      sum_grey += bilinear(grey, uv.x(), uv.y());
    }
    if (!all_hit) continue;
    if (hit_row != nullptr) hit_row[c] = (sum_W / step).cast<float>();
    if (all_seen) row[c] = float(sum_grey / step);
  }
}

// Interpolates, along the row, every run of at most `max_run` NaN pixels
// that has valid pixels on both sides; longer runs and runs at the ends
// stay NaN. Returns the pixels filled.
std::int64_t fillShortInvalidRuns(cv::Mat& strip, int max_run) {
  std::int64_t filled = 0;
  if (max_run <= 0) return filled;
  for (int r = 0; r < strip.rows; ++r) {
    float* row = strip.ptr<float>(r);
    int c = 0;
    while (c < strip.cols) {
      if (std::isfinite(row[c])) {
        ++c;
        continue;
      }
      const int begin = c;
      while (c < strip.cols && !std::isfinite(row[c])) ++c;
      const int length = c - begin;
      if (begin == 0 || c == strip.cols || length > max_run) continue;
      const float left = row[begin - 1], right = row[c];
      for (int k = 0; k < length; ++k) {
        const float a = float(k + 1) / float(length + 1);
        row[begin + k] = (1.0f - a) * left + a * right;
      }
      filled += length;
    }
  }
  return filled;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("StripTiePointOptions: " + what);
}

}  // namespace

void StripTiePointOptions::validate() const {
  require(sample_step >= 1, "sample_step must be >= 1");
  require(patch_lines >= 3 && patch_columns >= 3, "patch_lines and patch_columns must be >= 3");
  require(search_lines >= 1 && search_columns >= 1, "search_lines and search_columns must be >= 1");
  require(blur_sigma_m >= 0.0 && highpass_sigma_m >= 0.0,
          "blur_sigma_m and highpass_sigma_m must be >= 0");
  require(min_ncc > 0.0 && min_ncc <= 1.0, "min_ncc must be in (0, 1]");
  require(min_peak_margin >= 0.0 && exclusion_radius_m >= 0.0 && min_template_std >= 0.0 &&
              frame_margin_px >= 0.0,
          "min_peak_margin, exclusion_radius_m, min_template_std and frame_margin_px must be >= 0");
  require(line_phases >= 1 && line_phases <= 16, "line_phases must be in [1, 16]");
  require(fill_invalid_columns >= 0, "fill_invalid_columns must be >= 0");
}

StripTiePoints findStripTiePoints(const StripTiePointInputs& in, const StripTiePointOptions& o,
                                  std::ostream& log) {
  o.validate();
  if (in.cube == nullptr || in.uhi_camera == nullptr || in.mesh == nullptr ||
      in.frames == nullptr || in.rgb_camera == nullptr) {
    throw std::invalid_argument("findStripTiePoints: an input (cube, cameras, mesh, frames) is missing");
  }
  const EnviReader& cube = *in.cube;
  const int samples = in.uhi_camera->samples();
  const int bands = cube.bands();
  if (cube.samples() != samples) {
    throw std::invalid_argument("findStripTiePoints: the cube has " + std::to_string(cube.samples()) +
                                " samples, the UHI camera " + std::to_string(samples));
  }
  if (int(in.band_weights.size()) != bands) {
    throw std::invalid_argument("findStripTiePoints: " + std::to_string(in.band_weights.size()) +
                                " band weights for a cube of " + std::to_string(bands) + " bands");
  }
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };

  StripTiePoints out;
  const int step = o.sample_step;
  const int cols = samples / step;
  const int rows = int(in.lines.size());
  if (rows < o.patch_lines + 2 * o.search_lines || cols < o.patch_columns + 2 * o.search_columns ||
      in.frame_poses.empty()) {
    log << "strip tie points: too few lines, samples or posed frames for one patch\n";
    return out;
  }

  std::vector<int> used_bands;
  for (int b = 0; b < bands; ++b) {
    if (in.band_weights[std::size_t(b)] != 0.0) used_bands.push_back(b);
  }
  const std::optional<float> ignore = enviDataIgnoreValue(cube.header(), cube.headerPath());

  // 1. The real strip, and the prediction at each phase of the line
  // spacing (phase k: the poses interpolated k / P of the way to the next
  // line), with the surface point of every column at phase 0.
  const int P = o.line_phases;
  cv::Mat real(rows, cols, CV_32F, cv::Scalar(kNaN));
  std::vector<cv::Mat> predicted;
  for (int k = 0; k < P; ++k) predicted.emplace_back(rows, cols, CV_32F, cv::Scalar(kNaN));
  const Eigen::Vector3f no_hit = Eigen::Vector3f::Constant(kNaN);
  std::vector<Eigen::Vector3f> hit_W(std::size_t(rows) * std::size_t(cols), no_hit);
  auto hitAt = [&](int r, int c) -> Eigen::Vector3f& { return hit_W[std::size_t(r) * cols + c]; };

  const ScanLineCaster caster(*in.uhi_camera, *in.mesh);
  GreyFrames grey_frames(*in.frames);
  std::vector<float> pixel_major(std::size_t(samples) * std::size_t(bands));
  std::vector<std::uint8_t> non_finite(static_cast<std::size_t>(samples));
  std::vector<std::uint8_t> ignored(static_cast<std::size_t>(samples));
  std::vector<std::vector<ScanLineHits>> hits(static_cast<std::size_t>(P));
  std::vector<std::int64_t> chunk_lines;
  std::vector<SE3d> chunk_poses;
  // Each phase's exposure time per row of the chunk (for its nearest frame).
  std::vector<std::vector<double>> chunk_times(static_cast<std::size_t>(P));
  constexpr int kChunk = 128;
  for (int first = 0; first < rows; first += kChunk) {
    const int count = std::min(kChunk, rows - first);
    for (int k = 0; k < P; ++k) {
      chunk_lines.clear();
      chunk_poses.clear();
      chunk_times[std::size_t(k)].clear();
      for (int j = 0; j < count; ++j) {
        const int i = first + j;
        const RowPose pose =
            poseAt(in.lines, k == 0 || i + 1 >= rows ? double(i) : i + double(k) / P);
        chunk_lines.push_back(in.lines[std::size_t(i)].line);
        chunk_poses.push_back(pose.T);
        chunk_times[std::size_t(k)].push_back(pose.t);
      }
      caster.castLines(chunk_lines, chunk_poses, hits[std::size_t(k)]);
    }
    for (int j = 0; j < count; ++j) {
      const int i = first + j;
      cube.readLinePixelMajor(int(in.lines[std::size_t(i)].line), pixel_major.data());
      markInvalidSamples(pixel_major.data(), bands, samples, cube.header().data_type, ignore, non_finite.data(),
                         ignored.data());
      realStripRow(pixel_major.data(), non_finite.data(), ignored.data(), bands, step, used_bands,
                   in.band_weights, in.band_offset, cols, real.ptr<float>(i));
      for (int k = 0; k < P; ++k) {
        if (k > 0 && i + 1 >= rows) break;  // no line after the last to interpolate to
        // The prediction: each hit seen by the frame nearest in time.
        const double t = chunk_times[std::size_t(k)][std::size_t(j)];
        const auto& [frame_index, T_W_C] = in.frame_poses[nearestFrame(in.frame_poses, *in.frames, t)];
        const cv::Mat& grey = grey_frames.frame(frame_index);
        if (grey.empty()) continue;
        predictedStripRow(hits[std::size_t(k)][std::size_t(j)], T_W_C, grey, *in.rgb_camera,
                          o.frame_margin_px, step, cols, predicted[std::size_t(k)].ptr<float>(i),
                          k == 0 ? &hitAt(i, 0) : nullptr);
      }
    }
  }
  out.counts.filled_pixels = fillShortInvalidRuns(real, o.fill_invalid_columns);
  out.counts.frames_decoded = grey_frames.decoded();
  out.counts.frames_undecodable = grey_frames.undecodable();

  // 2. The strip's pixel on the ground, to state the band-pass in metres.
  std::vector<double> across, along;
  for (int r = 0; r + 1 < rows; r += 4) {
    for (int c = cols / 4; c < 3 * cols / 4; c += 16) {
      const Eigen::Vector3f& p = hitAt(r, c);
      const float a = (hitAt(r, c + 1) - p).norm(), b = (hitAt(r + 1, c) - p).norm();
      if (std::isfinite(a)) across.push_back(a);
      if (std::isfinite(b)) along.push_back(b);
    }
  }
  out.counts.across_pixel_m = upperMedian(across);
  out.counts.along_pixel_m = upperMedian(along);
  if (!(out.counts.across_pixel_m > 0.0) || !(out.counts.along_pixel_m > 0.0)) {
    log << "strip tie points: the scan lines do not hit the surface\n";
    return out;
  }
  const cv::Point2d metre_to_px(1.0 / out.counts.across_pixel_m, 1.0 / out.counts.along_pixel_m);
  const cv::Point2d blur = o.blur_sigma_m * metre_to_px, highpass = o.highpass_sigma_m * metre_to_px;
  const PreparedImage real_image = prepareForMatching(real, blur, highpass);
  std::vector<PreparedImage> predicted_images;
  for (cv::Mat& image : predicted) {
    predicted_images.push_back(prepareForMatching(image, blur, highpass));
    image.release();
  }
  hit_W = {};
  // The phases interleave into one score map whose rows are 1/P line apart.
  const cv::Point2d exclusion(o.exclusion_radius_m * metre_to_px.x,
                              o.exclusion_radius_m * metre_to_px.y * P);

  // 3. Each patch of the real strip searched in the prediction.
  const double min_std = o.min_template_std * real_image.stddev;
  const int H = o.patch_lines, W = o.patch_columns, SL = o.search_lines, SC = o.search_columns;
  cv::Mat phase_scores;
  cv::Mat scores(2 * SL * P + 1, 2 * SC + 1, CV_32F);
  const ScanLineCastOptions cast_options;
  for (int r0 = SL; r0 + H + SL <= rows; r0 += H) {
    for (int c0 = SC; c0 + W + SC <= cols; c0 += W) {
      const cv::Rect patch(c0, r0, W, H);
      const cv::Rect search(c0 - SC, r0 - SL, W + 2 * SC, H + 2 * SL);
      bool valid = allValid(real_image.valid, patch);
      for (int k = 0; k < P && valid; ++k) valid = allValid(predicted_images[std::size_t(k)].valid, search);
      if (!valid) continue;
      ++out.counts.patches;
      const cv::Mat templ = real_image.blurred(patch);
      cv::Scalar mean, stddev;
      cv::meanStdDev(templ, mean, stddev);
      if (stddev[0] < min_std || stddev[0] <= 0.0) continue;
      ++out.counts.textured;
      // Score row m = j * P + k: the template's first row on the
      // prediction's row (r0 - SL + j) at phase k, a shift of m / P - SL lines.
      for (int k = 0; k < P; ++k) {
        cv::matchTemplate(predicted_images[std::size_t(k)].blurred(search), templ, phase_scores,
                          cv::TM_CCOEFF_NORMED);
        for (int j = 0; j < phase_scores.rows; ++j) {
          const int m = j * P + k;
          if (m < scores.rows) phase_scores.row(j).copyTo(scores.row(m));
        }
      }
      const std::optional<NccPeak> peak =
          unambiguousPeak(scores, o.min_ncc, o.min_peak_margin, exclusion);
      if (!peak) continue;
      ++out.counts.matched;
      // The real patch's centre pixel and where the prediction put it: the
      // point that pixel saw is where the ray of that predicted position
      // meets the surface.
      const double real_row = r0 + (H - 1) / 2.0, real_col = c0 + (W - 1) / 2.0;
      const double row = real_row + peak->y / P - SL, col = real_col + peak->x - SC;
      if (row < 0.0 || row > rows - 1) continue;
      const SE3d T_W_U = poseAt(in.lines, row).T;
      const std::optional<Eigen::Vector3d> ray_U = in.uhi_camera->unproject(col * step + (step - 1) / 2.0);
      if (!ray_U) continue;
      Ray ray;
      ray.origin = T_W_U.t;
      ray.direction = (T_W_U.q * *ray_U).normalized();
      ray.t_near = cast_options.min_range_m;
      ray.t_far = cast_options.max_range_m;
      const RayHit hit = in.mesh->intersect(ray);
      if (hit.triangle < 0) continue;
      ExtrinsicTiePoint tie;
      const RowPose real_pose = poseAt(in.lines, real_row);
      tie.line_position = real_pose.line_position;
      tie.line = std::llround(tie.line_position);
      tie.sample = real_col * step + (step - 1) / 2.0;
      tie.p_W = ray.origin + hit.distance * ray.direction;
      tie.range_m = (tie.p_W - real_pose.T.t).norm();
      tie.hyper_col_row = Eigen::Vector2d(real_col, real_row);
      tie.rgb_col_row = Eigen::Vector2d(col, row);
      tie.ncc = peak->ncc;
      out.tie_points.push_back(tie);
    }
  }
  out.counts.tie_points = int(out.tie_points.size());
  log << "strip tie points: " << rows << " lines x " << cols << " columns (pixel "
      << fixedDecimals(out.counts.across_pixel_m * 1000.0, 2) << " mm across, "
      << fixedDecimals(out.counts.along_pixel_m * 1000.0, 2) << " mm along), "
      << out.counts.frames_decoded << " RGB frames"
      << (out.counts.frames_undecodable > 0
              ? " (" + std::to_string(out.counts.frames_undecodable) + " undecodable: their lines left out)"
              : std::string())
      << (out.counts.filled_pixels > 0
              ? "; " + std::to_string(out.counts.filled_pixels) + " unusable strip pixels interpolated"
              : std::string())
      << "; " << out.counts.patches << " patches, "
      << out.counts.textured << " textured, " << out.counts.matched << " matched, "
      << out.counts.tie_points << " tie points, " << fixedDecimals(seconds(), 1) << " s\n";
  return out;
}

}  // namespace hsmap
