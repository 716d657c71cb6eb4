#include "factors/spline_reprojection_factor.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/sized_cost_function.h>

#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/geometry/se3_bspline_jacobians.h"
#include "factors/factor_argument_checks.h"
#include "factors/pose_block_jacobian.h"
#include "factors/world_point_projection_jacobians.h"

namespace hsmap {

namespace {

constexpr int P = SE3d::kNumParameters;

std::vector<Key> keysOf(const SplineSegment& segment, Key landmark_p_W) {
  std::vector<Key> keys = activeControlPointKeys(segment);
  keys.push_back(landmark_p_W);
  return keys;
}

// The residual of SplineReprojectionResidual with analytic Jacobians: the
// pinhole projection's Jacobian with respect to the frame pose, chained
// through the spline to the four control points.
class SplineReprojectionCost final
    : public ceres::SizedCostFunction<SplineReprojectionFactor::kResidualDimension, P, P, P, P, 3> {
 public:
  SplineReprojectionCost(double u, const Eigen::Vector2d& pixel,
                         std::shared_ptr<const PinholeRadtanCamera> camera)
      : u_(u), pixel_(pixel), camera_(std::move(camera)) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const Eigen::Vector3d p_W(parameters[4][0], parameters[4][1], parameters[4][2]);
    if (jacobians == nullptr) {
      // Residual only (line search, cost checks): the pose alone is cheaper.
      const Eigen::Vector2d predicted = projectPinhole(
          evaluateSe3Spline(parameters, u_), p_W, camera_->intrinsics().data());
      residuals[0] = predicted.x() - pixel_.x();
      residuals[1] = predicted.y() - pixel_.y();
      return true;
    }
    const SE3SplineJacobians spline = SE3SplineJacobians::fromBlocks(parameters, u_);
    ProjectionJacobians projection;
    const Eigen::Vector2d predicted = projectWithJacobians(*camera_, spline.pose(), p_W, &projection);
    residuals[0] = predicted.x() - pixel_.x();
    residuals[1] = predicted.y() - pixel_.y();

    if (jacobians[0] != nullptr || jacobians[1] != nullptr || jacobians[2] != nullptr ||
        jacobians[3] != nullptr) {
      std::array<Eigen::Matrix<double, 2, 6>, 4> d_r_d_control_points;
      spline.chain<2>(projection.d_pose, &d_r_d_control_points);
      for (int k = 0; k < 4; ++k) {
        if (jacobians[k] == nullptr) continue;
        poseTangentToAmbientJacobian<2>(SE3d::fromParameters(parameters[k]),
                                        d_r_d_control_points[k], jacobians[k]);
      }
    }
    if (jacobians[4] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> d_r_d_p_W(jacobians[4]);
      d_r_d_p_W = projection.d_point;
    }
    return true;
  }

 private:
  double u_;
  Eigen::Vector2d pixel_;
  std::shared_ptr<const PinholeRadtanCamera> camera_;
};

}  // namespace

SplineReprojectionFactor::SplineReprojectionFactor(const SplineTiming& spline, double t_frame,
                                                   Key landmark_p_W, const Eigen::Vector2d& pixel,
                                                   const PinholeRadtanParameters& intrinsics,
                                                   NoiseModel noise, RobustLoss robust_loss)
    : SplineReprojectionFactor(spline, t_frame, landmark_p_W, pixel,
                               std::make_shared<const PinholeRadtanCamera>(intrinsics),
                               std::move(noise), robust_loss) {}

SplineReprojectionFactor::SplineReprojectionFactor(
    const SplineTiming& spline, double t_frame, Key landmark_p_W, const Eigen::Vector2d& pixel,
    std::shared_ptr<const PinholeRadtanCamera> camera, NoiseModel noise, RobustLoss robust_loss)
    : CeresFactor(keysOf(spline.segmentAt(t_frame), landmark_p_W), std::move(noise), robust_loss),
      t_frame_(t_frame),
      segment_(spline.segmentAt(t_frame)),
      pixel_(pixel),
      camera_(std::move(camera)) {
  if (camera_ == nullptr) {
    throw std::invalid_argument("SplineReprojectionFactor: the camera is null");
  }
  requireNoiseDimension("SplineReprojectionFactor", this->noise(), kResidualDimension);
  requireFinite("SplineReprojectionFactor", "pixel", pixel_);
}

std::unique_ptr<ceres::CostFunction> SplineReprojectionFactor::createCostFunction() const {
  return std::make_unique<SplineReprojectionCost>(segment_.u, pixel_, camera_);
}

std::unique_ptr<ceres::CostFunction> SplineReprojectionFactor::createAutoDiffCostFunction() const {
  return std::make_unique<
      ceres::AutoDiffCostFunction<SplineReprojectionResidual, kResidualDimension, P, P, P, P, 3>>(
      new SplineReprojectionResidual{segment_.u, pixel_, camera_->intrinsics()});
}

}  // namespace hsmap
