#include "core/geometry/rotation_anchored_alignment.h"

#include <Eigen/SVD>
#include <stdexcept>

namespace hsmap {

Eigen::Quaterniond chordalMeanRotation(const std::vector<Eigen::Quaterniond>& rotations) {
  if (rotations.empty()) throw std::invalid_argument("chordalMeanRotation: no rotations");
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (const auto& q : rotations) sum += q.normalized().toRotationMatrix();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sum, Eigen::ComputeFullU | Eigen::ComputeFullV);
  // The projection is unique when the two smallest singular values are not
  // both zero (the summed rotations do not cancel out).
  if (!(svd.singularValues()(1) > 1e-9 * double(rotations.size()))) {
    throw std::invalid_argument("chordalMeanRotation: the rotations cancel out; no unique mean");
  }
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return Eigen::Quaterniond(svd.matrixU() * D * svd.matrixV().transpose()).normalized();
}

Sim3 alignScaleTranslation(const Eigen::Quaterniond& q_B_A,
                           const std::vector<Eigen::Vector3d>& source,
                           const std::vector<Eigen::Vector3d>& target) {
  if (source.size() != target.size() || source.size() < 2) {
    throw std::invalid_argument("alignScaleTranslation: expected at least 2 pairs of points, got " +
                                std::to_string(source.size()) + " and " +
                                std::to_string(target.size()));
  }
  const double n = double(source.size());
  Eigen::Vector3d mean_A = Eigen::Vector3d::Zero(), mean_B = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < source.size(); ++i) {
    mean_A += source[i] / n;
    mean_B += target[i] / n;
  }
  double numerator = 0.0, denominator = 0.0;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const Eigen::Vector3d a = q_B_A * (source[i] - mean_A);
    numerator += a.dot(target[i] - mean_B);
    denominator += a.squaredNorm();
  }
  if (!(denominator > 0.0) || !(numerator > 0.0)) {
    throw std::invalid_argument(
        "alignScaleTranslation: the points do not move along each other; no positive scale fits");
  }
  const double s = numerator / denominator;
  return Sim3(s, q_B_A, mean_B - s * (q_B_A * mean_A));
}

}  // namespace hsmap
