#include "pipelines/surface/vertex_colours.h"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <map>

namespace hsmap {
namespace {

// Bilinear sample of an 8-bit BGR (or grey) image at (u, v), as RGB.
Eigen::Matrix<std::uint8_t, 3, 1> sampleRgb(const cv::Mat& image, const Eigen::Vector2d& pixel) {
  cv::Mat patch;
  cv::getRectSubPix(image, cv::Size(1, 1), cv::Point2f(float(pixel.x()), float(pixel.y())), patch);
  if (patch.channels() == 1) {
    const std::uint8_t g = patch.at<std::uint8_t>(0, 0);
    return {g, g, g};
  }
  const cv::Vec3b bgr = patch.at<cv::Vec3b>(0, 0);
  return {bgr[2], bgr[1], bgr[0]};
}

}  // namespace

VertexColours colourVerticesFromKeyframes(const SurfaceMesh& mesh, const VisibilityPoints& points,
                                          const VisualMap& map_W, const RgbFrameSource& frames,
                                          const PinholeRadtanCamera& camera) {
  VertexColours colours;
  colours.rgb.assign(mesh.vertices.size(), Eigen::Matrix<std::uint8_t, 3, 1>(128, 128, 128));
  // The chosen keyframe of every vertex, grouped so each image is decoded once.
  std::map<int, std::vector<std::pair<std::size_t, Eigen::Vector2d>>> by_keyframe;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const int point = mesh.point_index[v];
    int best = -1;
    double best_distance = 0.0;
    Eigen::Vector2d best_pixel;
    for (int k : points.views[std::size_t(point)]) {
      const Eigen::Vector3d p_C = map_W.keyframe(k).T_F_C.inverse() * points.p_W[std::size_t(point)];
      if (!(p_C.z() > 0.0)) continue;
      const Eigen::Vector2d pixel = camera.project(p_C);
      if (!camera.isInImage(pixel)) continue;
      const double distance = p_C.norm();
      if (best < 0 || distance < best_distance) {
        best = k;
        best_distance = distance;
        best_pixel = pixel;
      }
    }
    if (best < 0) {
      ++colours.uncoloured;
      continue;
    }
    by_keyframe[best].emplace_back(v, best_pixel);
  }
  for (const auto& [k, vertices] : by_keyframe) {
    cv::Mat image;
    try {
      image = frames.frame(map_W.keyframe(k).frame_index);
    } catch (const std::exception&) {
      colours.uncoloured += int(vertices.size());  // an undecodable frame: counted, left grey
      continue;
    }
    ++colours.images_decoded;
    for (const auto& [v, pixel] : vertices) colours.rgb[v] = sampleRgb(image, pixel);
  }
  return colours;
}

}  // namespace hsmap
