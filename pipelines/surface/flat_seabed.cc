#include "pipelines/surface/flat_seabed.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <sstream>

#include <Eigen/Dense>
#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/survey/ins_fixes_in_world.h"
#include "core/util/median.h"

namespace hsmap {
namespace {

constexpr double kDegree = M_PI / 180.0;
// Partner offsets in frames, climbed from the previous anchor's (step 2).
constexpr int kOffsets[] = {1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256, 384, 512};
constexpr int kOffsetCount = int(sizeof(kOffsets) / sizeof(kOffsets[0]));
constexpr int kFirstOffsetLevel = 5;  // 8 frames
// The ladder climbs past a passing pair only when it had this many times
// min_inliers (a pair near the threshold would most likely fail one step up).
constexpr int kClimbInlierFactor = 2;
// Two-point samples drawn by the known-rotation RANSAC (at 50% outliers, 200
// draws miss an all-inlier sample with probability 0.75^200).
constexpr int kRansacIterations = 200;
// Without INS attitude the start rotation is off by the vehicle's roll and
// pitch changes: the known-rotation RANSAC runs at this many times the
// threshold before the refinement.
constexpr double kNoAttitudeThresholdFactor = 5.0;

// One frame's ORB features, with each keypoint's undistorted normalised coordinates.
struct FrameFeatures {
  std::vector<cv::Point2f> normalised;
  cv::Mat descriptors;
};

class FeatureCache {
 public:
  FeatureCache(const Survey& survey, const SeabedDepthOptions& options)
      : survey_(survey), orb_(cv::ORB::create(options.orb_features)) {
    const PinholeRadtanParameters& p = survey.config.rgb.camera;
    K_ = (cv::Mat_<double>(3, 3) << p.fx, 0, p.cx, 0, p.fy, p.cy, 0, 0, 1);
    distortion_ = cv::Mat(1, 5, CV_64F);
    for (int i = 0; i < 5; ++i) distortion_.at<double>(i) = p.distortion[std::size_t(i)];
  }

  const FrameFeatures& at(int survey_index) {
    auto found = cache_.find(survey_index);
    if (found != cache_.end()) return found->second;
    FrameFeatures features;
    cv::Mat grey;
    cv::cvtColor(survey_.rgb.frame(survey_index), grey, cv::COLOR_BGR2GRAY);
    std::vector<cv::KeyPoint> keypoints;
    orb_->detectAndCompute(grey, cv::noArray(), keypoints, features.descriptors);
    if (!keypoints.empty()) {
      std::vector<cv::Point2f> pixels;
      for (const cv::KeyPoint& k : keypoints) pixels.push_back(k.pt);
      cv::undistortPoints(pixels, features.normalised, K_, distortion_);
    }
    return cache_.emplace(survey_index, std::move(features)).first->second;
  }

 private:
  const Survey& survey_;
  cv::Ptr<cv::ORB> orb_;
  cv::Mat K_, distortion_;
  std::map<int, FrameFeatures> cache_;
};

// Least-squares quadratic (linear with fewer than 6 fixes) through the fixes'
// body positions within the window around t_m; evaluates p_W_B(t).
class SmoothedBodyTrack {
 public:
  // nullopt when the window holds too few fixes or does not span [t1, t2].
  static std::optional<SmoothedBodyTrack> fit(const std::vector<InsFixInWorld>& fixes, double t1,
                                              double t2, double half_window_s, int min_fixes,
                                              int max_degree) {
    const double t_m = 0.5 * (t1 + t2);
    std::vector<const InsFixInWorld*> used;
    for (const InsFixInWorld& f : fixes) {
      if (std::abs(f.t - t_m) <= half_window_s) used.push_back(&f);
    }
    if (int(used.size()) < std::max(min_fixes, 2)) return std::nullopt;
    if (used.front()->t > t1 || used.back()->t < t2) return std::nullopt;
    SmoothedBodyTrack track;
    track.t_m_ = t_m;
    // Three fixes per coefficient at least, else a lower degree.
    track.degree_ = std::clamp(int(used.size()) / 3 - 1, 1, max_degree);
    Eigen::MatrixXd A(used.size(), track.degree_ + 1);
    Eigen::MatrixXd b(used.size(), 3);
    for (std::size_t k = 0; k < used.size(); ++k) {
      const double dt = used[k]->t - t_m;
      double power = 1.0;
      for (int d = 0; d <= track.degree_; ++d, power *= dt) A(Eigen::Index(k), d) = power;
      b.row(Eigen::Index(k)) = used[k]->p_W_B.transpose();
    }
    track.coefficients_ = A.colPivHouseholderQr().solve(b);
    return track;
  }

  Eigen::Vector3d at(double t) const {
    const double dt = t - t_m_;
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    double power = 1.0;
    for (int d = 0; d <= degree_; ++d, power *= dt) p += power * coefficients_.row(d).transpose();
    return p;
  }

 private:
  double t_m_ = 0.0;
  int degree_ = 1;
  Eigen::MatrixXd coefficients_;  // (degree + 1) x 3
};

// The translation direction t (unit, p_C2 = R p_C1 + t) of a pair whose
// rotation R is known, from normalised matches: the epipolar constraint
// x2 . (t x R x1) = t . (R x1 x x2) = 0 is linear in t, so two matches give
// t = n_a x n_b (n = R x1 x x2). RANSAC over such pairs (fixed seed) scores
// the distance of x2 to its epipolar line t x R x1; t is then the least-
// squares null vector of the inliers' n (SVD), its sign the one that puts
// most inliers in front of C1. A flat scene does not make this ambiguous,
// unlike the essential matrix (Longuet-Higgins 1984: a plane admits two).
std::optional<Eigen::Vector3d> translationWithKnownRotation(const std::vector<cv::Point2f>& x1,
                                                            const std::vector<cv::Point2f>& x2,
                                                            const Eigen::Matrix3d& R_C2_C1,
                                                            double threshold,
                                                            std::vector<unsigned char>& inlier) {
  const std::size_t n = x1.size();
  inlier.assign(n, 0);
  if (n < 2) return std::nullopt;
  std::vector<Eigen::Vector3d> r1(n), h2(n), normals(n);
  for (std::size_t i = 0; i < n; ++i) {
    r1[i] = R_C2_C1 * Eigen::Vector3d(x1[i].x, x1[i].y, 1.0);
    h2[i] = Eigen::Vector3d(x2[i].x, x2[i].y, 1.0);
    normals[i] = r1[i].cross(h2[i]);
  }
  auto isInlier = [&](const Eigen::Vector3d& t, std::size_t i) {
    const Eigen::Vector3d line = t.cross(r1[i]);
    const double norm = line.head<2>().norm();
    return norm > 0.0 && std::abs(h2[i].dot(line)) / norm < threshold;
  };
  cv::RNG rng(0x5eab3d);
  Eigen::Vector3d best = Eigen::Vector3d::Zero();
  int best_count = 0;
  for (int iteration = 0; iteration < kRansacIterations; ++iteration) {
    const std::size_t a = std::size_t(rng.uniform(0, int(n)));
    const std::size_t b = std::size_t(rng.uniform(0, int(n)));
    const Eigen::Vector3d t = normals[a].cross(normals[b]);
    if (a == b || t.norm() < 1e-12) continue;
    const Eigen::Vector3d t_unit = t.normalized();
    int count = 0;
    for (std::size_t i = 0; i < n; ++i) count += isInlier(t_unit, i) ? 1 : 0;
    if (count > best_count) {
      best_count = count;
      best = t_unit;
    }
  }
  if (best_count < 2) return std::nullopt;
  Eigen::MatrixXd A(best_count, 3);
  int row = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (isInlier(best, i)) A.row(row++) = normals[i].normalized().transpose();
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  Eigen::Vector3d t = svd.matrixV().col(2);
  // Cheirality: with p_C2 = d1 R x1 + t = d2 x2, d1 from the two rays' closest approach.
  int in_front = 0, behind = 0;
  for (std::size_t i = 0; i < n; ++i) {
    inlier[i] = isInlier(t, i) ? 1 : 0;
    if (!inlier[i]) continue;
    // Minimise |d1 r1 + t - d2 h2|: d1 = ((h2.t)(h2.r1) - (h2.h2)(r1.t)) / ((r1.r1)(h2.h2) - (r1.h2)^2).
    const double rr = r1[i].dot(r1[i]), hh = h2[i].dot(h2[i]), rh = r1[i].dot(h2[i]);
    const double d1 = (h2[i].dot(t) * rh - hh * r1[i].dot(t)) / (rr * hh - rh * rh);
    (d1 > 0.0 ? in_front : behind) += 1;
  }
  if (behind > in_front) t = -t;
  return t;
}

// Sampson distance (normalised units) of a match to the epipolar geometry
// E = [t]x R (Hartley & Zisserman, eq. 11.9).
double sampsonDistance(const Eigen::Matrix3d& E, const Eigen::Vector3d& h1, const Eigen::Vector3d& h2) {
  const Eigen::Vector3d Ex1 = E * h1;
  const Eigen::Vector3d Etx2 = E.transpose() * h2;
  const double denominator = Ex1.head<2>().squaredNorm() + Etx2.head<2>().squaredNorm();
  return denominator > 0.0 ? std::abs(h2.dot(Ex1)) / std::sqrt(denominator) : 0.0;
}

Eigen::Matrix3d crossMatrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

// Refines R and the unit t of a pair from a nearby start by Gauss-Newton on
// the inliers' Sampson distances (numeric Jacobian; R updated on the left by
// exp(w), t within its tangent plane), then re-selects the inliers at
// `threshold` and refines once more. Used without INS attitude, where the
// planar poses' rotation (level, along the track) is only a start: a local
// refinement from the right neighbourhood stays clear of the flat scene's
// second solution, which lies far away (t along the normal).
void refineRelativePose(const std::vector<cv::Point2f>& x1, const std::vector<cv::Point2f>& x2,
                        double threshold, Eigen::Matrix3d& R, Eigen::Vector3d& t,
                        std::vector<unsigned char>& inlier) {
  const std::size_t n = x1.size();
  std::vector<Eigen::Vector3d> h1(n), h2(n);
  for (std::size_t i = 0; i < n; ++i) {
    h1[i] = Eigen::Vector3d(x1[i].x, x1[i].y, 1.0);
    h2[i] = Eigen::Vector3d(x2[i].x, x2[i].y, 1.0);
  }
  for (int round = 0; round < 2; ++round) {
    std::vector<std::size_t> used;
    for (std::size_t i = 0; i < n; ++i) {
      if (inlier[i]) used.push_back(i);
    }
    if (used.size() < 8) return;
    for (int iteration = 0; iteration < 10; ++iteration) {
      // Tangent basis of t.
      Eigen::Vector3d b1 = t.unitOrthogonal();
      Eigen::Vector3d b2 = t.cross(b1);
      auto residuals = [&](const Eigen::Matrix<double, 5, 1>& delta) {
        const Eigen::Matrix3d R_d =
            Eigen::AngleAxisd(delta.head<3>().norm(), delta.head<3>().norm() > 0.0
                                                          ? Eigen::Vector3d(delta.head<3>().normalized())
                                                          : Eigen::Vector3d::UnitX())
                .toRotationMatrix() * R;
        const Eigen::Vector3d t_d = (t + delta(3) * b1 + delta(4) * b2).normalized();
        const Eigen::Matrix3d E = crossMatrix(t_d) * R_d;
        Eigen::VectorXd r(Eigen::Index(used.size()));
        for (std::size_t k = 0; k < used.size(); ++k) {
          const Eigen::Vector3d Ex1 = E * h1[used[k]];
          const Eigen::Vector3d Etx2 = E.transpose() * h2[used[k]];
          const double d = Ex1.head<2>().squaredNorm() + Etx2.head<2>().squaredNorm();
          r(Eigen::Index(k)) = d > 0.0 ? h2[used[k]].dot(Ex1) / std::sqrt(d) : 0.0;
        }
        return r;
      };
      const Eigen::Matrix<double, 5, 1> zero = Eigen::Matrix<double, 5, 1>::Zero();
      const Eigen::VectorXd r0 = residuals(zero);
      Eigen::MatrixXd J(r0.size(), 5);
      constexpr double kStep = 1e-7;
      for (int j = 0; j < 5; ++j) {
        Eigen::Matrix<double, 5, 1> delta = zero;
        delta(j) = kStep;
        J.col(j) = (residuals(delta) - r0) / kStep;
      }
      const Eigen::Matrix<double, 5, 1> step = (J.transpose() * J).ldlt().solve(-J.transpose() * r0);
      if (!step.allFinite()) return;
      const Eigen::Vector3d w = step.head<3>();
      if (w.norm() > 0.0) R = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix() * R;
      t = (t + step(3) * b1 + step(4) * b2).normalized();
      if (step.norm() < 1e-10) break;
    }
    const Eigen::Matrix3d E = crossMatrix(t) * R;
    for (std::size_t i = 0; i < n; ++i) inlier[i] = sampsonDistance(E, h1[i], h2[i]) < threshold ? 1 : 0;
  }
}

// Why pairs failed, counted over every pair tried.
struct FailureCounts {
  int no_ins_window = 0;
  int few_inliers = 0;
  int low_parallax = 0;
  int direction = 0;
  int few_points = 0;
};

struct PairResult {
  int inliers = 0;
  double seabed_z = 0.0;
  double altitude = 0.0;
  long long points = 0;
};

// Steps 2-6 for one anchor/partner pair; nullopt (with the reason counted) when it fails.
std::optional<PairResult> evaluatePair(const GeorefFramePose& anchor, const GeorefFramePose& partner,
                                       FeatureCache& features, const std::vector<InsFixInWorld>& fixes,
                                       const SE3d& T_B_C, const SeabedDepthOptions& options,
                                       double focal_px, bool use_ins_rotation, FailureCounts& failures) {
  const std::optional<SmoothedBodyTrack> track = SmoothedBodyTrack::fit(
      fixes, anchor.t, partner.t, options.ins_half_window_s, options.min_window_fixes,
      options.ins_fit_degree);
  if (!track) {
    ++failures.no_ins_window;
    return std::nullopt;
  }
  const FrameFeatures& f1 = features.at(anchor.index);
  const FrameFeatures& f2 = features.at(partner.index);
  if (f1.descriptors.rows < options.min_inliers || f2.descriptors.rows < options.min_inliers) {
    ++failures.few_inliers;
    return std::nullopt;
  }
  cv::BFMatcher matcher(cv::NORM_HAMMING);
  std::vector<std::vector<cv::DMatch>> knn;
  matcher.knnMatch(f1.descriptors, f2.descriptors, knn, 2);
  std::vector<cv::Point2f> x1, x2;
  for (const std::vector<cv::DMatch>& m : knn) {
    if (m.size() < 2 || m[0].distance >= options.match_ratio * m[1].distance) continue;
    x1.push_back(f1.normalised[std::size_t(m[0].queryIdx)]);
    x2.push_back(f2.normalised[std::size_t(m[0].trainIdx)]);
  }
  if (int(x1.size()) < options.min_inliers) {
    ++failures.few_inliers;
    return std::nullopt;
  }
  // The camera's baseline from the smoothed INS track, with the lever arm.
  auto cameraCentre = [&](const GeorefFramePose& frame) -> Eigen::Vector3d {
    const Eigen::Matrix3d R_W_B = frame.T_W_C.q.toRotationMatrix() * T_B_C.q.toRotationMatrix().transpose();
    return track->at(frame.t) + R_W_B * T_B_C.t;
  };
  const Eigen::Vector3d b_ins_W = cameraCentre(partner) - cameraCentre(anchor);
  const double scale = b_ins_W.norm();
  const Eigen::Matrix3d R_W_C1 = anchor.T_W_C.q.toRotationMatrix();

  // Rotation: the planar poses' (the INS's attitude; without one, level and
  // along the track: then only a start, refined below).
  Eigen::Matrix3d R_C2_C1 = (partner.T_W_C.q.conjugate() * anchor.T_W_C.q).toRotationMatrix();
  const double threshold = options.ransac_threshold_px / focal_px;
  std::vector<unsigned char> inlier;
  const std::optional<Eigen::Vector3d> t = translationWithKnownRotation(
      x1, x2, R_C2_C1, use_ins_rotation ? threshold : kNoAttitudeThresholdFactor * threshold, inlier);
  if (!t) {
    ++failures.few_inliers;
    return std::nullopt;
  }
  Eigen::Vector3d t_C2_C1 = *t;  // unit
  if (!use_ins_rotation) refineRelativePose(x1, x2, threshold, R_C2_C1, t_C2_C1, inlier);
  const int inliers = int(std::count(inlier.begin(), inlier.end(), 1));
  if (inliers < options.min_inliers) {
    ++failures.few_inliers;
    return std::nullopt;
  }
  cv::Mat R_cv(3, 3, CV_64F), t_cv(3, 1, CV_64F);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R_cv.at<double>(r, c) = R_C2_C1(r, c);
    t_cv.at<double>(r) = t_C2_C1(r);
  }

  // Visual baseline (unit, C2's centre in C1) in W, against the INS one.
  const Eigen::Vector3d b_visual_W = R_W_C1 * (-R_C2_C1.transpose() * t_C2_C1);
  const double cos_max_error = std::cos(options.max_direction_error_deg * kDegree);
  if (!(scale > 0.0) || b_visual_W.dot(b_ins_W) < scale * b_visual_W.norm() * cos_max_error) {
    ++failures.direction;
    return std::nullopt;
  }

  // Triangulate the inliers in C1 (P1 = [I | 0], P2 = [R | t]).
  std::vector<cv::Point2f> in1, in2;
  for (std::size_t i = 0; i < inlier.size(); ++i) {
    if (inlier[i]) {
      in1.push_back(x1[i]);
      in2.push_back(x2[i]);
    }
  }
  cv::Mat P1 = cv::Mat::eye(3, 4, CV_64F);
  cv::Mat P2(3, 4, CV_64F);
  R_cv.copyTo(P2.colRange(0, 3));
  t_cv.copyTo(P2.col(3));
  cv::Mat X;
  cv::triangulatePoints(P1, P2, in1, in2, X);
  X.convertTo(X, CV_64F);
  std::vector<double> parallax_deg, below_m;
  const Eigen::Vector3d c2_C1 = -R_C2_C1.transpose() * t_C2_C1;
  for (int i = 0; i < X.cols; ++i) {
    const double w = X.at<double>(3, i);
    if (std::abs(w) < 1e-12) continue;
    const Eigen::Vector3d p_C1(X.at<double>(0, i) / w, X.at<double>(1, i) / w, X.at<double>(2, i) / w);
    const Eigen::Vector3d p_C2 = R_C2_C1 * p_C1 + t_C2_C1;
    if (p_C1.z() <= 0.0 || p_C2.z() <= 0.0) continue;
    const Eigen::Vector3d ray1 = p_C1.normalized();
    const Eigen::Vector3d ray2 = (p_C1 - c2_C1).normalized();
    parallax_deg.push_back(std::acos(std::clamp(ray1.dot(ray2), -1.0, 1.0)) / kDegree);
    const double dz = (R_W_C1 * (scale * p_C1)).z();
    if (dz > 0.0) below_m.push_back(dz);
  }
  if (int(parallax_deg.size()) < options.min_inliers) {
    ++failures.few_inliers;
    return std::nullopt;
  }
  if (median(parallax_deg) < options.min_parallax_deg) {
    ++failures.low_parallax;
    return std::nullopt;
  }
  if (int(below_m.size()) < options.min_inliers) {
    ++failures.few_points;
    return std::nullopt;
  }
  PairResult result;
  result.altitude = median(below_m);
  result.inliers = inliers;
  result.seabed_z = anchor.T_W_C.t.z() + result.altitude;
  result.points = static_cast<long long>(below_m.size());
  return result;
}

std::string formatted(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, value);
  return buffer;
}

}  // namespace

std::string SeabedDepthOptions::validate() const {
  if (anchor_frames < 1) return "anchor_frames must be at least 1";
  if (orb_features < 10) return "orb_features must be at least 10";
  if (!(match_ratio > 0.0 && match_ratio <= 1.0)) return "match_ratio must be in (0, 1]";
  if (!(ransac_threshold_px > 0.0 && std::isfinite(ransac_threshold_px)))
    return "ransac_threshold_px must be finite and > 0";
  if (min_inliers < 8) return "min_inliers must be at least 8";
  if (!(min_parallax_deg >= 0.0 && min_parallax_deg < 90.0)) return "min_parallax_deg must be in [0, 90)";
  if (!(max_direction_error_deg > 0.0 && max_direction_error_deg <= 180.0))
    return "max_direction_error_deg must be in (0, 180]";
  if (!(ins_half_window_s > 0.0 && std::isfinite(ins_half_window_s)))
    return "ins_half_window_s must be finite and > 0";
  if (min_window_fixes < 2) return "min_window_fixes must be at least 2";
  if (ins_fit_degree < 1 || ins_fit_degree > 4) return "ins_fit_degree must be in [1, 4]";
  if (min_pairs < 1) return "min_pairs must be at least 1";
  return {};
}

std::string SeabedDepthEstimate::summary() const {
  return "seabed at z = " + formatted("%.3f", depth_m) + " m (altitude " + formatted("%.3f", altitude_m) +
         " m) from " + std::to_string(pairs) + " frame pairs, " + std::to_string(points) +
         " points, spread " + formatted("%.3f", spread_m) + " m, " + formatted("%.1f", seconds) + " s";
}

SeabedDepthEstimate estimateSeabedDepth(const Survey& survey, const std::vector<GeorefFramePose>& frames,
                                        const SeabedDepthOptions& options) {
  if (const std::string problem = options.validate(); !problem.empty()) {
    throw std::invalid_argument("seabed depth options: " + problem);
  }
  const auto start = std::chrono::steady_clock::now();
  const std::vector<InsFixInWorld> fixes = insFixesInWorld(survey);
  const SE3d T_B_C(survey.config.ins.T_B_C.rotation, survey.config.ins.T_B_C.translation_m);
  const double focal_px = 0.5 * (survey.config.rgb.camera.fx + survey.config.rgb.camera.fy);

  // Step 1: frames within the INS span, anchors spread over them.
  std::vector<int> eligible;  // positions in `frames`
  if (!fixes.empty()) {
    for (std::size_t i = 0; i < frames.size(); ++i) {
      if (frames[i].t >= fixes.front().t && frames[i].t <= fixes.back().t) eligible.push_back(int(i));
    }
  }
  const auto unavailable = [&](const std::string& why) {
    return SeabedDepthUnavailable("cannot estimate the seabed depth from the survey: " + why +
                                  " (give the depth with --seabed-depth)");
  };
  if (eligible.size() < 2) {
    throw unavailable(std::to_string(eligible.size()) + " of " + std::to_string(frames.size()) +
                      " RGB frames lie within the INS fixes' time span; two-view triangulation needs "
                      "at least 2");
  }
  const int anchor_count = std::min<int>(options.anchor_frames, int(eligible.size()) - 1);
  FeatureCache features(survey, options);
  FailureCounts failures;
  std::vector<double> seabed_z, altitudes;
  long long points = 0;
  int level = kFirstOffsetLevel;
  for (int a = 0; a < anchor_count; ++a) {
    // Anchors at evenly spaced positions of `eligible`, the last one leaving room for a partner.
    const int e = int(std::lround(double(a) * double(eligible.size() - 2) / std::max(1, anchor_count - 1)));
    const GeorefFramePose& anchor = frames[std::size_t(eligible[std::size_t(e)])];
    auto tryLevel = [&](int l) -> std::optional<PairResult> {
      const int partner = e + kOffsets[l];
      if (partner >= int(eligible.size())) return std::nullopt;
      return evaluatePair(anchor, frames[std::size_t(eligible[std::size_t(partner)])], features, fixes,
                          T_B_C, options, focal_px, survey.ins.has_attitude, failures);
    };
    // Largest usable level: no offset beyond the last frame.
    int top = 0;
    while (top + 1 < kOffsetCount && e + kOffsets[top + 1] < int(eligible.size())) ++top;
    level = std::min(level, top);
    std::optional<PairResult> best = tryLevel(level);
    int best_level = level;
    if (best) {
      // Climb only while the pair keeps a comfortable margin of inliers:
      // each failed climb costs a frame's decoding, features and matching.
      for (int l = level + 1; l <= top && best->inliers >= kClimbInlierFactor * options.min_inliers; ++l) {
        std::optional<PairResult> next = tryLevel(l);
        if (!next) break;
        best = next;
        best_level = l;
      }
    } else {
      for (int l = level - 1; l >= 0 && !best; --l) {
        best = tryLevel(l);
        best_level = l;
      }
    }
    if (!best) continue;
    level = best_level;
    seabed_z.push_back(best->seabed_z);
    altitudes.push_back(best->altitude);
    points += best->points;
  }

  if (int(seabed_z.size()) < options.min_pairs) {
    std::ostringstream why;
    why << seabed_z.size() << " of " << anchor_count << " anchor frames found a partner frame, "
        << options.min_pairs << " needed; pairs failed for too few matches or inliers ("
        << failures.few_inliers << "), too little parallax (" << failures.low_parallax
        << "), a visual baseline disagreeing with the INS (" << failures.direction
        << "), too few INS fixes around the pair (" << failures.no_ins_window
        << "), too few points below the camera (" << failures.few_points << ")";
    throw unavailable(why.str());
  }
  SeabedDepthEstimate estimate;
  estimate.depth_m = median(seabed_z);
  estimate.altitude_m = median(altitudes);
  estimate.pairs = int(seabed_z.size());
  estimate.points = points;
  std::vector<double> deviations;
  for (double z : seabed_z) deviations.push_back(std::abs(z - estimate.depth_m));
  estimate.spread_m = median(deviations);
  estimate.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return estimate;
}

PlyMesh flatSeabedMesh(double depth_m, const std::vector<Eigen::Vector3d>& positions_W, double margin_m,
                       double cell_m) {
  if (positions_W.empty()) throw std::invalid_argument("flatSeabedMesh: no positions to cover");
  if (!std::isfinite(depth_m)) throw std::invalid_argument("flatSeabedMesh: the depth is not finite");
  if (!(std::isfinite(margin_m) && margin_m >= 0.0))
    throw std::invalid_argument("flatSeabedMesh: the margin must be finite and >= 0");
  if (!(std::isfinite(cell_m) && cell_m > 0.0))
    throw std::invalid_argument("flatSeabedMesh: the cell size must be finite and > 0");
  Eigen::Vector2d lo = positions_W.front().head<2>(), hi = lo;
  for (const Eigen::Vector3d& p : positions_W) {
    if (!p.allFinite()) throw std::invalid_argument("flatSeabedMesh: a position is not finite");
    lo = lo.cwiseMin(p.head<2>());
    hi = hi.cwiseMax(p.head<2>());
  }
  lo.array() -= margin_m;
  hi.array() += margin_m;
  // At least one cell per axis, even for a single position and no margin.
  const int nx = std::max(1, int(std::ceil((hi.x() - lo.x()) / cell_m)));
  const int ny = std::max(1, int(std::ceil((hi.y() - lo.y()) / cell_m)));
  const double step_x = std::max(hi.x() - lo.x(), cell_m) / nx;
  const double step_y = std::max(hi.y() - lo.y(), cell_m) / ny;
  PlyMesh mesh;
  mesh.vertices.reserve(std::size_t(nx + 1) * std::size_t(ny + 1));
  for (int i = 0; i <= nx; ++i) {
    for (int j = 0; j <= ny; ++j) {
      mesh.vertices.emplace_back(lo.x() + i * step_x, lo.y() + j * step_y, depth_m);
    }
  }
  mesh.colors.assign(mesh.vertices.size(), Eigen::Matrix<std::uint8_t, 3, 1>(128, 128, 128));
  const auto vertex = [ny](int i, int j) { return i * (ny + 1) + j; };
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      // (north, east) x (east, north) order: (e_y x e_x) = -z, the normal points up.
      mesh.triangles.emplace_back(vertex(i, j), vertex(i, j + 1), vertex(i + 1, j));
      mesh.triangles.emplace_back(vertex(i + 1, j), vertex(i, j + 1), vertex(i + 1, j + 1));
    }
  }
  return mesh;
}

}  // namespace hsmap
