#include "core/geometry/sim3.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

namespace hsmap {

namespace {

// A point set is degenerate for alignment when its centred extent along the
// second principal axis is below this fraction of the extent along the
// first: the points lie on a line up to rounding, not up to noise.
constexpr double kCollinearRatio = 1e-8;
// ... and it coincides when the first extent is below this fraction of the
// points' magnitude (what centring leaves of identical points is rounding).
constexpr double kCoincidentRatio = 1e-12;

enum class Degeneracy { none, coincident, collinear };

// RMS extents of the centred points along their principal axes, largest first.
Eigen::Vector3d principalExtents(const Eigen::Matrix3Xd& points) {
  const Eigen::Vector3d centroid = points.rowwise().mean();
  const Eigen::Matrix3Xd centred = points.colwise() - centroid;
  const Eigen::Matrix3d scatter = centred * centred.transpose() / static_cast<double>(points.cols());
  // Eigenvalues come in increasing order; rounding can make the zero ones
  // slightly negative.
  const Eigen::Vector3d eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter, Eigen::EigenvaluesOnly).eigenvalues();
  return eigenvalues.reverse().cwiseMax(0.0).cwiseSqrt();
}

Degeneracy degeneracyOf(const Eigen::Matrix3Xd& points) {
  const Eigen::Vector3d extents = principalExtents(points);
  const double magnitude = points.colwise().norm().maxCoeff();
  if (extents[0] <= kCoincidentRatio * magnitude) return Degeneracy::coincident;
  if (extents[1] <= kCollinearRatio * extents[0]) return Degeneracy::collinear;
  return Degeneracy::none;
}

Eigen::Matrix3Xd toMatrix(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Matrix3Xd m(3, points.size());
  for (std::size_t i = 0; i < points.size(); ++i) m.col(static_cast<Eigen::Index>(i)) = points[i];
  return m;
}

Eigen::Matrix3Xd selectColumns(const Eigen::Matrix3Xd& points, const std::vector<std::size_t>& indices) {
  Eigen::Matrix3Xd m(3, indices.size());
  for (std::size_t k = 0; k < indices.size(); ++k) {
    m.col(static_cast<Eigen::Index>(k)) = points.col(static_cast<Eigen::Index>(indices[k]));
  }
  return m;
}

// Eigen::umeyama returns [c R, t; 0, 1]; det(c R) = c^3 recovers c. nullopt
// when the scale is not a positive finite number (rounding on a collapsed
// target).
std::optional<Sim3> umeyamaSim3(const Eigen::Matrix3Xd& source, const Eigen::Matrix3Xd& target,
                                bool estimate_scale) {
  const Eigen::Matrix4d m = Eigen::umeyama(source, target, estimate_scale);
  const Eigen::Matrix3d scaled_rotation = m.topLeftCorner<3, 3>();
  const double scale = estimate_scale ? std::cbrt(scaled_rotation.determinant()) : 1.0;
  if (!(std::isfinite(scale) && scale > 0.0)) return std::nullopt;
  const Eigen::Quaterniond q(Eigen::Matrix3d(scaled_rotation / scale));
  return Sim3(scale, q.normalized(), m.topRightCorner<3, 1>());
}

[[noreturn]] void invalid(const std::string& function, const std::string& detail) {
  throw std::invalid_argument(function + ": " + detail);
}

// The input checks shared by both alignments (see sim3.h).
void checkPairs(const std::string& function, const std::vector<Eigen::Vector3d>& source,
                const std::vector<Eigen::Vector3d>& target) {
  if (source.size() != target.size()) {
    invalid(function, "source and target must pair up, got " + std::to_string(source.size()) +
                          " source and " + std::to_string(target.size()) + " target points");
  }
  if (source.size() < 3) {
    invalid(function, "at least 3 point pairs are needed, got " + std::to_string(source.size()));
  }
  for (std::size_t i = 0; i < source.size(); ++i) {
    if (!source[i].allFinite() || !target[i].allFinite()) {
      invalid(function, "point pair " + std::to_string(i) + " is not finite");
    }
  }
}

void checkSpread(const std::string& function, const std::string& which,
                 const Eigen::Matrix3Xd& points) {
  switch (degeneracyOf(points)) {
    case Degeneracy::coincident:
      invalid(function, "the " + which +
                            " points all coincide, so the alignment is undetermined (degenerate)");
    case Degeneracy::collinear:
      invalid(function, "the " + which +
                            " points are collinear, so the rotation about their line is "
                            "undetermined (degenerate); they must span at least a plane");
    case Degeneracy::none:
      break;
  }
}

Sim3 alignChecked(const std::string& function, const Eigen::Matrix3Xd& source,
                  const Eigen::Matrix3Xd& target, bool estimate_scale) {
  checkSpread(function, "source", source);
  checkSpread(function, "target", target);
  const std::optional<Sim3> sim3 = umeyamaSim3(source, target, estimate_scale);
  if (!sim3) invalid(function, "the estimated scale is not a positive number (degenerate target)");
  return *sim3;
}

// Three distinct indices in [0, n), drawn straight from the generator (its
// output is fixed by the standard, the distributions' are not).
std::vector<std::size_t> drawSample(std::mt19937& rng, std::size_t n) {
  std::vector<std::size_t> sample;
  while (sample.size() < 3) {
    const std::size_t index = static_cast<std::size_t>(rng()) % n;
    if (std::find(sample.begin(), sample.end(), index) == sample.end()) sample.push_back(index);
  }
  return sample;
}

// Squared alignment errors |target_i - S source_i|^2 of every pair.
Eigen::VectorXd squaredErrors(const Sim3& sim3, const Eigen::Matrix3Xd& source,
                              const Eigen::Matrix3Xd& target) {
  Eigen::VectorXd errors(source.cols());
  for (Eigen::Index i = 0; i < source.cols(); ++i) {
    errors[i] = (target.col(i) - sim3.apply(source.col(i))).squaredNorm();
  }
  return errors;
}

struct Consensus {
  std::vector<std::size_t> inliers;
  double squared_error_sum = std::numeric_limits<double>::infinity();

  bool betterThan(const Consensus& other) const {
    if (inliers.size() != other.inliers.size()) return inliers.size() > other.inliers.size();
    return squared_error_sum < other.squared_error_sum;
  }
};

Consensus consensusOf(const Eigen::VectorXd& squared_errors, double threshold) {
  Consensus consensus;
  consensus.squared_error_sum = 0.0;
  for (Eigen::Index i = 0; i < squared_errors.size(); ++i) {
    if (squared_errors[i] <= threshold * threshold) {
      consensus.inliers.push_back(static_cast<std::size_t>(i));
      consensus.squared_error_sum += squared_errors[i];
    }
  }
  return consensus;
}

}  // namespace

Sim3::Sim3() : s_(1.0), q_(Eigen::Quaterniond::Identity()), t_(Eigen::Vector3d::Zero()) {}

Sim3::Sim3(double scale, const Eigen::Quaterniond& rotation, const Eigen::Vector3d& translation)
    : s_(scale), q_(rotation), t_(translation) {
  if (!(std::isfinite(scale) && scale > 0.0)) {
    std::ostringstream message;
    message << "Sim3: the scale must be a finite number > 0, got " << scale;
    throw std::invalid_argument(message.str());
  }
  const double norm = rotation.norm();
  if (!(std::isfinite(norm) && norm > 0.0) || !translation.allFinite()) {
    throw std::invalid_argument("Sim3: the rotation must be a finite non-zero quaternion and the "
                                "translation finite");
  }
  q_.normalize();
}

Eigen::Matrix4d Sim3::matrix() const {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = s_ * q_.toRotationMatrix();
  m.topRightCorner<3, 1>() = t_;
  return m;
}

Sim3 Sim3::operator*(const Sim3& S_B_A) const {
  return Sim3(s_ * S_B_A.s_, q_ * S_B_A.q_, s_ * (q_ * S_B_A.t_) + t_);
}

Sim3 Sim3::inverse() const {
  const Eigen::Quaterniond q_inv = q_.conjugate();
  return Sim3(1.0 / s_, q_inv, -(q_inv * t_) / s_);
}

SE3d Sim3::transformPose(const SE3d& T_A_C) const {
  return SE3d(q_ * T_A_C.q, apply(T_A_C.t));
}

Sim3 alignUmeyama(const std::vector<Eigen::Vector3d>& source,
                  const std::vector<Eigen::Vector3d>& target, bool estimate_scale) {
  checkPairs("alignUmeyama", source, target);
  return alignChecked("alignUmeyama", toMatrix(source), toMatrix(target), estimate_scale);
}

RobustAlignment alignUmeyamaRobust(const std::vector<Eigen::Vector3d>& source,
                                   const std::vector<Eigen::Vector3d>& target,
                                   double inlier_threshold, bool estimate_scale) {
  const std::string function = "alignUmeyamaRobust";
  checkPairs(function, source, target);
  if (!(std::isfinite(inlier_threshold) && inlier_threshold > 0.0)) {
    std::ostringstream message;
    message << "the inlier threshold must be a finite distance > 0, got " << inlier_threshold;
    invalid(function, message.str());
  }
  const Eigen::Matrix3Xd source_points = toMatrix(source);
  const Eigen::Matrix3Xd target_points = toMatrix(target);
  checkSpread(function, "source", source_points);

  // 1. RANSAC over minimal samples.
  std::mt19937 rng(kRobustAlignmentSeed);
  Consensus best;
  best.inliers.clear();
  for (int iteration = 0; iteration < kRobustAlignmentIterations; ++iteration) {
    const std::vector<std::size_t> sample = drawSample(rng, source.size());
    const Eigen::Matrix3Xd sample_source = selectColumns(source_points, sample);
    const Eigen::Matrix3Xd sample_target = selectColumns(target_points, sample);
    if (degeneracyOf(sample_source) != Degeneracy::none ||
        degeneracyOf(sample_target) != Degeneracy::none) {
      continue;
    }
    const std::optional<Sim3> model = umeyamaSim3(sample_source, sample_target, estimate_scale);
    if (!model) continue;
    const Consensus consensus =
        consensusOf(squaredErrors(*model, source_points, target_points), inlier_threshold);
    if (consensus.betterThan(best)) best = consensus;
  }

  // 2. Least-squares refit on the consensus set, which must itself span a plane.
  const Eigen::Matrix3Xd inlier_source = selectColumns(source_points, best.inliers);
  const Eigen::Matrix3Xd inlier_target = selectColumns(target_points, best.inliers);
  if (best.inliers.size() < 3 || degeneracyOf(inlier_source) != Degeneracy::none ||
      degeneracyOf(inlier_target) != Degeneracy::none) {
    throw std::runtime_error(
        function + ": no alignment is supported by 3 or more pairs that span a plane (best " +
        "consensus: " + std::to_string(best.inliers.size()) + " of " +
        std::to_string(source.size()) + " pairs); is the inlier threshold too small?");
  }
  const std::optional<Sim3> refit = umeyamaSim3(inlier_source, inlier_target, estimate_scale);
  if (!refit) {
    throw std::runtime_error(function + ": the refit on the consensus set has no positive scale");
  }

  // 3. One re-classification against the refit.
  RobustAlignment result;
  result.sim3 = *refit;
  const Eigen::VectorXd errors = squaredErrors(result.sim3, source_points, target_points);
  const Consensus final_consensus = consensusOf(errors, inlier_threshold);
  result.inliers.assign(source.size(), false);
  for (const std::size_t i : final_consensus.inliers) result.inliers[i] = true;
  result.inlier_count = final_consensus.inliers.size();
  result.inlier_rms = result.inlier_count == 0
                          ? 0.0
                          : std::sqrt(final_consensus.squared_error_sum /
                                      static_cast<double>(result.inlier_count));
  return result;
}

}  // namespace hsmap
