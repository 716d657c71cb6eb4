#include "pipelines/report/mesh_top_view.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace hsmap {

double MeshTopView::downAt(double north, double east) const {
  const int column = int(std::floor((east - east_min) / pixel_m));
  const int row = int(std::floor((north_max - north) / pixel_m));
  if (column < 0 || row < 0 || column >= down.cols || row >= down.rows) return NAN;
  return down.at<float>(row, column);
}

MeshTopView rasteriseMeshTopView(const PlyMesh& mesh, int max_side) {
  if (mesh.triangles.empty()) throw std::invalid_argument("rasteriseMeshTopView: the mesh has no triangles");
  double north_min = std::numeric_limits<double>::infinity(), north_max = -north_min;
  double east_min = north_min, east_max = -north_min;
  for (const Eigen::Vector3d& v : mesh.vertices) {
    north_min = std::min(north_min, v.x());
    north_max = std::max(north_max, v.x());
    east_min = std::min(east_min, v.y());
    east_max = std::max(east_max, v.y());
  }
  MeshTopView view;
  view.pixel_m = std::max({north_max - north_min, east_max - east_min, 1e-6}) / max_side;
  view.north_max = north_max;
  view.east_min = east_min;
  const int columns = std::max(1, int(std::ceil((east_max - east_min) / view.pixel_m)));
  const int rows = std::max(1, int(std::ceil((north_max - north_min) / view.pixel_m)));
  view.down = cv::Mat(rows, columns, CV_32F, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  // The page's image background (report.css), where no triangle lies.
  view.image = cv::Mat(rows, columns, CV_8UC3, cv::Scalar(40, 34, 30));

  // Light from the north-west, 45 degrees up: relief facing it is lit.
  const Eigen::Vector3d light_W = Eigen::Vector3d(1.0, -1.0, -std::sqrt(2.0)).normalized();
  const bool coloured = mesh.colors.size() == mesh.vertices.size();
  for (const Eigen::Vector3i& triangle : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[std::size_t(triangle[0])];
    const Eigen::Vector3d& b = mesh.vertices[std::size_t(triangle[1])];
    const Eigen::Vector3d& c = mesh.vertices[std::size_t(triangle[2])];
    Eigen::Vector3d normal = (b - a).cross(c - a);
    if (normal.norm() == 0.0) continue;
    normal.normalize();
    if (normal.z() > 0) normal = -normal;  // the side facing up (down < 0)
    const double shade = 0.35 + 0.65 * std::max(0.0, normal.dot(light_W));
    // Pixel coordinates (x = column, y = row) of the corners.
    const auto pixel = [&](const Eigen::Vector3d& v) {
      return Eigen::Vector2d((v.y() - east_min) / view.pixel_m, (north_max - v.x()) / view.pixel_m);
    };
    const Eigen::Vector2d pa = pixel(a), pb = pixel(b), pc = pixel(c);
    const double area = (pb - pa).x() * (pc - pa).y() - (pb - pa).y() * (pc - pa).x();
    if (std::abs(area) < 1e-12) continue;
    const int x0 = std::max(0, int(std::floor(std::min({pa.x(), pb.x(), pc.x()}))));
    const int x1 = std::min(columns - 1, int(std::ceil(std::max({pa.x(), pb.x(), pc.x()}))));
    const int y0 = std::max(0, int(std::floor(std::min({pa.y(), pb.y(), pc.y()}))));
    const int y1 = std::min(rows - 1, int(std::ceil(std::max({pa.y(), pb.y(), pc.y()}))));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector2d p(x + 0.5, y + 0.5);
        // Barycentric weights of b and c; a's is the rest.
        const double wb = ((p - pa).x() * (pc - pa).y() - (p - pa).y() * (pc - pa).x()) / area;
        const double wc = ((pb - pa).x() * (p - pa).y() - (pb - pa).y() * (p - pa).x()) / area;
        const double wa = 1.0 - wb - wc;
        if (wa < 0 || wb < 0 || wc < 0) continue;
        const float down = float(wa * a.z() + wb * b.z() + wc * c.z());
        float& depth = view.down.at<float>(y, x);
        if (!std::isnan(depth) && depth <= down) continue;
        depth = down;
        Eigen::Vector3d rgb(170, 170, 170);
        if (coloured) {
          rgb = wa * mesh.colors[std::size_t(triangle[0])].cast<double>() +
                wb * mesh.colors[std::size_t(triangle[1])].cast<double>() +
                wc * mesh.colors[std::size_t(triangle[2])].cast<double>();
        }
        view.image.at<cv::Vec3b>(y, x) = cv::Vec3b(cv::saturate_cast<uchar>(shade * rgb.z()),
                                                   cv::saturate_cast<uchar>(shade * rgb.y()),
                                                   cv::saturate_cast<uchar>(shade * rgb.x()));
      }
    }
  }
  return view;
}

}  // namespace hsmap
