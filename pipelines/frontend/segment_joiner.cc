#include "pipelines/frontend/segment_joiner.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <opencv2/features2d.hpp>

#include "core/geometry/so3.h"
#include "core/util/median.h"

namespace hsmap {

namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

std::string formatted(const char* format, double a, double b) {
  char text[160];
  std::snprintf(text, sizeof(text), format, a, b);
  return text;
}

}  // namespace

JoinKeyframeView makeJoinView(const VisualMap& map, int keyframe_id, const Sim3& S_X_map, cv::Mat gray) {
  const Keyframe& keyframe = map.keyframe(keyframe_id);
  JoinKeyframeView view;
  view.keyframe_id = keyframe_id;
  view.segment = keyframe.segment;
  view.T_X_C = S_X_map.transformPose(keyframe.T_F_C);
  for (const auto& o : keyframe.observations) {
    const Landmark& l = map.landmark(o.landmark_id);
    if (!l.valid || l.keyframe_ids.size() < 2) continue;
    view.landmark_ids.push_back(o.landmark_id);
    view.p_X.push_back(S_X_map.apply(l.p_F));
    view.pixels.push_back(o.pixel);
  }
  view.gray = std::move(gray);
  return view;
}

void describeJoinView(JoinKeyframeView& view, const SegmentJoinOptions& options) {
  const bool sift = options.descriptor == "sift";
  if (!sift && options.descriptor != "orb") {
    throw std::invalid_argument("segment join descriptor must be \"sift\" or \"orb\", not \"" + options.descriptor +
                                "\"");
  }
  std::vector<cv::KeyPoint> keypoints;
  keypoints.reserve(view.pixels.size());
  const float size = sift ? float(options.sift_size_px) : float(options.orb_patch_px);
  for (std::size_t i = 0; i < view.pixels.size(); ++i) {
    // Upright (angle 0), at the full image (octave 0); class_id keeps the
    // observation, as compute() drops keypoints too close to the border.
    keypoints.emplace_back(cv::Point2f(float(view.pixels[i].x()), float(view.pixels[i].y())), size, 0.0f, 0.0f, 0,
                           int(i));
  }
  view.descriptors.release();
  view.described.clear();
  if (keypoints.empty() || view.gray.empty()) return;
  if (sift) {
    // Float descriptors (CV_32F rows) at the given size and angle.
    cv::SIFT::create()->compute(view.gray, keypoints, view.descriptors);
    for (const auto& k : keypoints) view.described.push_back(k.class_id);
    return;
  }
  // One pyramid level; the edge threshold just covers the upright patch.
  const int patch = options.orb_patch_px;
  cv::Ptr<cv::ORB> orb = cv::ORB::create(int(keypoints.size()) + 1, 1.2f, 1, patch / 2 + 1, 0, 2,
                                         cv::ORB::HARRIS_SCORE, patch);
  orb->compute(view.gray, keypoints, view.descriptors);
  for (const auto& k : keypoints) view.described.push_back(k.class_id);
}

SegmentJoin joinKeyframePair(const JoinKeyframeView& earlier, const JoinKeyframeView& later,
                             const PinholeRadtanCamera& camera, const SegmentJoinOptions& options) {
  SegmentJoin join;
  join.earlier_keyframe = earlier.keyframe_id;
  join.new_keyframe = later.keyframe_id;
  join.earlier_segment = earlier.segment;
  join.descriptor = options.descriptor;
  if (earlier.descriptors.rows < 2 || later.descriptors.rows < 2) {
    join.failure = "too few landmarks to describe";
    return join;
  }

  // 2. Mutual best matches that pass the ratio test.
  const bool binary = earlier.descriptors.type() == CV_8U;
  cv::BFMatcher matcher(binary ? cv::NORM_HAMMING : cv::NORM_L2);
  std::vector<std::vector<cv::DMatch>> forward, backward;
  matcher.knnMatch(later.descriptors, earlier.descriptors, forward, 2);
  matcher.knnMatch(earlier.descriptors, later.descriptors, backward, 2);
  std::vector<std::pair<int, int>> matched;  // (earlier observation, later observation)
  for (const auto& m : forward) {
    if (m.size() < 2) continue;
    if ((binary && m[0].distance > options.max_hamming) || m[0].distance >= options.ratio * m[1].distance) continue;
    const auto& back = backward[std::size_t(m[0].trainIdx)];
    if (back.empty() || back[0].trainIdx != m[0].queryIdx) continue;
    matched.emplace_back(earlier.described[std::size_t(m[0].trainIdx)],
                         later.described[std::size_t(m[0].queryIdx)]);
  }
  join.matches = int(matched.size());
  if (join.matches < options.min_inliers) {
    join.failure = std::to_string(join.matches) + " descriptor matches, fewer than " +
                   std::to_string(options.min_inliers);
    return join;
  }

  // 3. PnP of the new keyframe on the earlier landmarks.
  std::vector<PoseCorrespondence> correspondences;
  std::vector<Eigen::Vector3d> p_S, p_G;
  std::vector<std::pair<int, int>> pairs;  // matched, of each correspondence
  for (const auto& [e, n] : matched) {
    PoseCorrespondence c;
    c.p_F = earlier.p_X[std::size_t(e)];
    c.pixel = later.pixels[std::size_t(n)];
    const auto ray = camera.unproject(c.pixel);
    if (!ray || !(ray->z() > 0.0)) continue;
    c.normalized = ray->head<2>() / ray->z();
    correspondences.push_back(c);
    p_G.push_back(earlier.p_X[std::size_t(e)]);
    p_S.push_back(later.p_X[std::size_t(n)]);
    pairs.emplace_back(e, n);
  }
  const PoseEstimate pnp = estimateFramePose(correspondences, earlier.T_X_C, camera, options.pnp);
  join.pnp_inliers = pnp.inlier_count;
  if (!pnp.ok) {
    join.failure = "PnP: " + pnp.failure;
    return join;
  }

  // 4. Sim(3) of the pairs, RANSAC at a fraction of the altitude.
  std::vector<double> depths;
  for (const auto& p : p_G) {
    const double z = (earlier.T_X_C.inverse() * p).z();
    if (z > 0.0) depths.push_back(z);
  }
  const double altitude = upperMedian(depths);
  if (!(altitude > 0.0)) {
    join.failure = "the earlier landmarks are not in front of their keyframe";
    return join;
  }
  join.altitude = altitude;
  RobustAlignment sim3;
  try {
    sim3 = alignUmeyamaRobust(p_S, p_G, options.sim3_threshold_fraction * altitude, true);
  } catch (const std::exception& error) {
    join.failure = std::string("Sim(3): ") + error.what();
    return join;
  }
  join.S_G_S = sim3.sim3;
  join.sim3_inliers = int(sim3.inlier_count);

  // 5. Verification: the two poses of the new keyframe agree ...
  const SE3d T_G_N_sim3 = join.S_G_S.transformPose(later.T_X_C);
  join.rotation_gap_deg = logSO3(Eigen::Quaterniond(pnp.T_F_C.q.conjugate() * T_G_N_sim3.q)).norm() * kRadToDeg;
  join.position_gap_fraction = (pnp.T_F_C.t - T_G_N_sim3.t).norm() / altitude;
  // ... and the pairs reproject in both keyframes under the joined map.
  const SE3d T_E_G = earlier.T_X_C.inverse(), T_N_G = T_G_N_sim3.inverse();
  std::vector<std::size_t> verified;
  double sum_sq = 0.0;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto [e, n] = pairs[k];
    if (!sim3.inliers[k] || !pnp.inliers[k]) continue;
    const Eigen::Vector3d in_E = T_E_G * p_G[k], in_N = T_N_G * p_G[k];
    if (!(in_E.z() > 0.0) || !(in_N.z() > 0.0)) continue;
    const double error_E = (camera.project(in_E) - earlier.pixels[std::size_t(e)]).squaredNorm();
    const double error_N = (camera.project(in_N) - later.pixels[std::size_t(n)]).squaredNorm();
    const double limit = options.max_reprojection_px * options.max_reprojection_px;
    if (error_E > limit || error_N > limit) continue;
    verified.push_back(k);
    sum_sq += error_E + error_N;
    join.landmark_pairs.emplace_back(earlier.landmark_ids[std::size_t(e)], later.landmark_ids[std::size_t(n)]);
  }
  join.inliers = int(verified.size());
  join.reprojection_rms_px = verified.empty() ? 0.0 : std::sqrt(sum_sq / (2.0 * double(verified.size())));

  // The scale's 1-sigma: least-squares standard error over the inliers.
  if (verified.size() >= 3) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (std::size_t k : verified) mean += p_S[k];
    mean /= double(verified.size());
    double spread = 0.0, residual = 0.0;
    for (std::size_t k : verified) {
      spread += (p_S[k] - mean).squaredNorm();
      residual += (p_G[k] - join.S_G_S.apply(p_S[k])).squaredNorm();
    }
    const double dof = std::max(1.0, 3.0 * double(verified.size()) - 7.0);
    join.scale_sigma = spread > 0.0 ? std::sqrt(residual / dof / spread) : 0.0;
  }

  if (join.rotation_gap_deg > options.max_rotation_deg) {
    join.failure = formatted("the PnP and Sim(3) poses differ by %.2f deg (at most %.2f)", join.rotation_gap_deg,
                             options.max_rotation_deg);
    return join;
  }
  if (join.position_gap_fraction > options.max_position_fraction) {
    join.failure = formatted("the PnP and Sim(3) positions differ by %.1f %% of the altitude (at most %.1f %%)",
                             100.0 * join.position_gap_fraction, 100.0 * options.max_position_fraction);
    return join;
  }
  if (join.inliers < options.min_inliers) {
    join.failure = std::to_string(join.inliers) + " verified pairs of " + std::to_string(join.matches) +
                   " matches, fewer than " + std::to_string(options.min_inliers);
    return join;
  }
  if (2 * join.inliers < join.sim3_inliers) {
    join.failure = std::to_string(join.inliers) + " of the Sim(3)'s " + std::to_string(join.sim3_inliers) +
                   " inliers reproject, fewer than half";
    return join;
  }
  join.ok = true;
  return join;
}

std::vector<std::pair<int, int>> pairsUnderSimilarity(const JoinKeyframeView& earlier, const JoinKeyframeView& later,
                                                      const PinholeRadtanCamera& camera, const Sim3& S_G_S,
                                                      double threshold_G, const SegmentJoinOptions& options) {
  std::vector<std::pair<int, int>> pairs;
  if (earlier.descriptors.empty() || later.descriptors.empty()) return pairs;
  const SE3d T_E_G = earlier.T_X_C.inverse();
  const SE3d T_N_G = S_G_S.transformPose(later.T_X_C).inverse();
  const double limit = options.max_reprojection_px * options.max_reprojection_px;
  const int norm = earlier.descriptors.type() == CV_8U ? cv::NORM_HAMMING : cv::NORM_L2;
  // The new views' described rows in G.
  std::vector<Eigen::Vector3d> new_G(std::size_t(later.descriptors.rows));
  for (int r = 0; r < later.descriptors.rows; ++r) {
    new_G[std::size_t(r)] = S_G_S.apply(later.p_X[std::size_t(later.described[std::size_t(r)])]);
  }
  auto gated = [&](int er, int nr) {
    const std::size_t e = std::size_t(earlier.described[std::size_t(er)]);
    const std::size_t n = std::size_t(later.described[std::size_t(nr)]);
    const Eigen::Vector3d& p_G = earlier.p_X[e];
    const Eigen::Vector3d& q_G = new_G[std::size_t(nr)];
    if ((p_G - q_G).norm() > threshold_G) return false;
    const Eigen::Vector3d in_N = T_N_G * p_G, in_E = T_E_G * q_G;
    if (!(in_N.z() > 0.0) || !(in_E.z() > 0.0)) return false;
    return (camera.project(in_N) - later.pixels[n]).squaredNorm() <= limit &&
           (camera.project(in_E) - earlier.pixels[e]).squaredNorm() <= limit;
  };
  // Nearest descriptor among the gated candidates, both ways.
  std::vector<int> best_new(std::size_t(earlier.descriptors.rows), -1);
  std::vector<double> best_new_distance(best_new.size(), 0.0);
  std::vector<int> best_earlier(std::size_t(later.descriptors.rows), -1);
  std::vector<double> best_earlier_distance(best_earlier.size(), 0.0);
  for (int er = 0; er < earlier.descriptors.rows; ++er) {
    for (int nr = 0; nr < later.descriptors.rows; ++nr) {
      if (!gated(er, nr)) continue;
      const double d = cv::norm(earlier.descriptors.row(er), later.descriptors.row(nr), norm);
      if (norm == cv::NORM_HAMMING && d > options.max_hamming) continue;
      if (best_new[std::size_t(er)] < 0 || d < best_new_distance[std::size_t(er)]) {
        best_new[std::size_t(er)] = nr;
        best_new_distance[std::size_t(er)] = d;
      }
      if (best_earlier[std::size_t(nr)] < 0 || d < best_earlier_distance[std::size_t(nr)]) {
        best_earlier[std::size_t(nr)] = er;
        best_earlier_distance[std::size_t(nr)] = d;
      }
    }
  }
  std::vector<std::pair<int, int>> mutual;  // rows
  std::vector<double> distances;
  for (int er = 0; er < earlier.descriptors.rows; ++er) {
    const int nr = best_new[std::size_t(er)];
    if (nr < 0 || best_earlier[std::size_t(nr)] != er) continue;
    mutual.emplace_back(er, nr);
    distances.push_back(best_new_distance[std::size_t(er)]);
  }
  // Where a landmark's own partner is not among the other keyframe's
  // landmarks, another one may still pass the gates by chance (150
  // landmarks in 480x360 px put one within 3 px of a given pixel 2.5 % of
  // the time); its descriptor is of another patch: a distance beyond twice
  // the median of the pairs is refused.
  const double limit_distance = distances.size() >= 10 ? 2.0 * upperMedian(distances) : 0.0;
  for (std::size_t i = 0; i < mutual.size(); ++i) {
    if (limit_distance > 0.0 && distances[i] > limit_distance) continue;
    const auto [er, nr] = mutual[i];
    pairs.emplace_back(earlier.landmark_ids[std::size_t(earlier.described[std::size_t(er)])],
                       later.landmark_ids[std::size_t(later.described[std::size_t(nr)])]);
  }
  return pairs;
}

}  // namespace hsmap
