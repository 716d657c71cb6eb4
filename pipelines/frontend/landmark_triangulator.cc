#include "pipelines/frontend/landmark_triangulator.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace hsmap {

const char* toString(TriangulationOutcome outcome) {
  switch (outcome) {
    case TriangulationOutcome::ok: return "ok";
    case TriangulationOutcome::low_parallax: return "low parallax";
    case TriangulationOutcome::behind_camera: return "behind a camera";
    case TriangulationOutcome::reprojection: return "reprojection error";
    case TriangulationOutcome::degenerate: return "degenerate";
  }
  return "?";
}

std::optional<Eigen::Vector3d> triangulateLinear(const std::vector<TriangulationView>& views) {
  if (views.size() < 2) return std::nullopt;
  Eigen::MatrixXd A(2 * views.size(), 4);
  for (std::size_t i = 0; i < views.size(); ++i) {
    const SE3d T_C_F = views[i].T_F_C.inverse();
    Eigen::Matrix<double, 3, 4> P;
    P.leftCols<3>() = T_C_F.rotationMatrix();
    P.col(3) = T_C_F.t;
    const Eigen::Vector3d ray = Eigen::Vector3d(views[i].normalized.x(), views[i].normalized.y(), 1.0).normalized();
    // Two rows of ray x (P p): independent for any ray with z != 0.
    const Eigen::RowVector4d r0 = ray.y() * P.row(2) - ray.z() * P.row(1);
    const Eigen::RowVector4d r1 = ray.z() * P.row(0) - ray.x() * P.row(2);
    A.row(Eigen::Index(2 * i)) = r0;
    A.row(Eigen::Index(2 * i + 1)) = r1;
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::Vector4d h = svd.matrixV().col(3);
  if (!(std::abs(h(3)) > 1e-12 * h.head<3>().norm()) || !h.allFinite()) return std::nullopt;
  return Eigen::Vector3d(h.head<3>() / h(3));
}

double rayParallax(const std::vector<TriangulationView>& views) {
  double best = 0.0;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const Eigen::Vector3d a =
        views[i].T_F_C.q * Eigen::Vector3d(views[i].normalized.x(), views[i].normalized.y(), 1.0).normalized();
    for (std::size_t j = i + 1; j < views.size(); ++j) {
      const Eigen::Vector3d b =
          views[j].T_F_C.q * Eigen::Vector3d(views[j].normalized.x(), views[j].normalized.y(), 1.0).normalized();
      best = std::max(best, std::atan2(a.cross(b).norm(), a.dot(b)));
    }
  }
  return best;
}

TriangulationResult triangulateLandmark(const std::vector<TriangulationView>& views,
                                        const PinholeRadtanCamera& camera,
                                        const TriangulationLimits& limits) {
  TriangulationResult result;
  const auto p_F = triangulateLinear(views);
  if (!p_F) return result;
  result.p_F = *p_F;
  // Parallax at the point: the angle its rays from the camera centres make.
  double parallax = 0.0;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const Eigen::Vector3d a = (*p_F - views[i].T_F_C.t).normalized();
    for (std::size_t j = i + 1; j < views.size(); ++j) {
      const Eigen::Vector3d b = (*p_F - views[j].T_F_C.t).normalized();
      parallax = std::max(parallax, std::atan2(a.cross(b).norm(), a.dot(b)));
    }
  }
  result.parallax_rad = parallax;
  double worst = 0.0;
  for (const auto& view : views) {
    const Eigen::Vector3d p_C = view.T_F_C.inverse() * *p_F;
    if (!(p_C.z() > 0.0)) {
      result.outcome = TriangulationOutcome::behind_camera;
      return result;
    }
    worst = std::max(worst, (camera.project(p_C) - view.pixel).norm());
  }
  result.max_error_px = worst;
  if (parallax < limits.min_angle_rad) {
    result.outcome = TriangulationOutcome::low_parallax;
  } else if (worst > limits.max_error_px) {
    result.outcome = TriangulationOutcome::reprojection;
  } else {
    result.outcome = TriangulationOutcome::ok;
  }
  return result;
}

}  // namespace hsmap
