#pragma once
// The survey's INS fixes in the world frame W: each (lat, lon, depth) as the
// body position p_W_B through LocalNedFrame at the survey's origin
// (GeographicLib; docs/SURVEY_FORMAT.md), and, when ins.csv has attitude,
// its roll, pitch and heading as R_W_B (ZYX, body to NED). Geo-referencing
// and the evaluation's INS floor both start from these.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <vector>

namespace hsmap {

struct Survey;

struct InsFixInWorld {
  double t = 0.0;
  Eigen::Vector3d p_W_B = Eigen::Vector3d::Zero();
  std::optional<Eigen::Quaterniond> q_W_B;  // when ins.csv has attitude
  long long line_number = 0;                // line in ins.csv (0 when not read from a file)
};

std::vector<InsFixInWorld> insFixesInWorld(const Survey& survey);

}  // namespace hsmap
