// VisibilityPoints::validate and SurfaceCutOptions::validate name what is wrong.
#include "pipelines/surface/visibility_points.h"

#include <gtest/gtest.h>

#include "pipelines/surface/surface_cut_options.h"

namespace hsmap {
namespace {

VisibilityPoints twoPoints() {
  VisibilityPoints points;
  points.p_W = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0)};
  points.views = {{0}, {0, 1}};
  points.c_W = {Eigen::Vector3d(0, 0, 5), Eigen::Vector3d(1, 0, 5)};
  return points;
}

TEST(VisibilityPoints, ValidPointsHaveNoProblem) {
  EXPECT_EQ(twoPoints().validate(), "");
  VisibilityPoints weighted = twoPoints();
  weighted.weights = {1.0, 0.5};
  EXPECT_EQ(weighted.validate(), "");
  EXPECT_DOUBLE_EQ(weighted.weight(1), 0.5);
  EXPECT_DOUBLE_EQ(twoPoints().weight(1), 1.0);
}

TEST(VisibilityPoints, NamesTheProblem) {
  VisibilityPoints points = twoPoints();
  points.views.pop_back();
  EXPECT_NE(points.validate().find("views has 1 entries for 2 points"), std::string::npos);
  points = twoPoints();
  points.views[1].push_back(2);
  EXPECT_NE(points.validate().find("point 1 names camera 2 of 2"), std::string::npos);
  points = twoPoints();
  points.weights = {1.0, 0.0};
  EXPECT_NE(points.validate().find("point 1 has weight"), std::string::npos);
  points = twoPoints();
  points.p_W[0].x() = std::nan("");
  EXPECT_NE(points.validate().find("point 0 is not finite"), std::string::npos);
  points = twoPoints();
  points.p_W[1] = points.c_W[1];
  EXPECT_NE(points.validate().find("point 1 lies at the centre of camera 1"), std::string::npos);
}

TEST(SurfaceCutOptions, DefaultsAreValidAndBadValuesNamed) {
  EXPECT_EQ(SurfaceCutOptions{}.validate(), "");
  SurfaceCutOptions options;
  options.visibility_weight = 0.0;
  EXPECT_NE(options.validate().find("visibility_weight"), std::string::npos);
  options = {};
  options.area_weight = -1.0;
  EXPECT_NE(options.validate().find("area_weight"), std::string::npos);
  options = {};
  options.max_cells_per_ray = 0;
  EXPECT_NE(options.validate().find("max_cells_per_ray"), std::string::npos);
}

}  // namespace
}  // namespace hsmap
