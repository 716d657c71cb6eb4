#include "pipelines/surface/surface_tiles.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace hsmap {

Eigen::AlignedBox2d depthFootprint(const Keyframe& keyframe, const StereoPartner& partner,
                                   const PinholeRadtanCamera& camera) {
  Eigen::AlignedBox2d box;
  const double w = camera.width() - 1.0;
  const double h = camera.height() - 1.0;
  for (double u : {0.0, w / 2, w}) {
    for (double v : {0.0, h / 2, h}) {
      const std::optional<Eigen::Vector3d> ray = camera.unproject({u, v});
      if (!ray || !(ray->z() > 0.0)) continue;
      for (double z : {partner.min_depth_m, partner.max_depth_m}) {
        const Eigen::Vector3d p_W = keyframe.T_F_C * Eigen::Vector3d(*ray * (z / ray->z()));
        box.extend(p_W.head<2>());
      }
    }
  }
  box.extend(keyframe.T_F_C.t.head<2>());
  return box;
}

std::vector<SurfaceTile> layOutTiles(const VisualMap& map_W,
                                     const std::vector<std::optional<StereoPartner>>& partners,
                                     const PinholeRadtanCamera& camera, double size, double margin) {
  std::map<std::pair<long, long>, SurfaceTile> tiles;
  for (const Keyframe& keyframe : map_W.keyframes()) {
    const auto& partner = partners[std::size_t(keyframe.id)];
    if (!partner) continue;
    const Eigen::AlignedBox2d box = depthFootprint(keyframe, *partner, camera);
    const long x0 = long(std::floor((box.min().x() - margin) / size));
    const long x1 = long(std::floor((box.max().x() + margin) / size));
    const long y0 = long(std::floor((box.min().y() - margin) / size));
    const long y1 = long(std::floor((box.max().y() + margin) / size));
    for (long ix = x0; ix <= x1; ++ix) {
      for (long iy = y0; iy <= y1; ++iy) {
        SurfaceTile& tile = tiles[{ix, iy}];
        if (tile.keyframes.empty()) {
          tile.core = Eigen::AlignedBox2d(Eigen::Vector2d(double(ix) * size, double(iy) * size),
                                          Eigen::Vector2d(double(ix + 1) * size, double(iy + 1) * size));
          tile.padded = Eigen::AlignedBox2d(tile.core.min().array() - margin,
                                            tile.core.max().array() + margin);
        }
        tile.keyframes.push_back(keyframe.id);
      }
    }
  }
  std::vector<SurfaceTile> ordered;
  for (auto& [index, tile] : tiles) ordered.push_back(std::move(tile));
  std::stable_sort(ordered.begin(), ordered.end(), [](const SurfaceTile& a, const SurfaceTile& b) {
    return a.keyframes.front() < b.keyframes.front();
  });
  return ordered;
}


bool inHalfOpen(const Eigen::AlignedBox2d& box, const Eigen::Vector2d& p) {
  return p.x() >= box.min().x() && p.x() < box.max().x() && p.y() >= box.min().y() &&
         p.y() < box.max().y();
}

SurfaceMesh cropToTile(const SurfaceMesh& mesh, const Eigen::AlignedBox2d& core) {
  SurfaceMesh cropped;
  std::vector<int> remap(mesh.vertices.size(), -1);
  for (const Eigen::Vector3i& triangle : mesh.triangles) {
    const Eigen::Vector3d centroid = (mesh.vertices[std::size_t(triangle[0])] +
                                      mesh.vertices[std::size_t(triangle[1])] +
                                      mesh.vertices[std::size_t(triangle[2])]) / 3.0;
    if (!inHalfOpen(core, centroid.head<2>())) continue;
    Eigen::Vector3i kept;
    for (int c = 0; c < 3; ++c) {
      int& index = remap[std::size_t(triangle[c])];
      if (index < 0) {
        index = int(cropped.vertices.size());
        cropped.vertices.push_back(mesh.vertices[std::size_t(triangle[c])]);
        cropped.point_index.push_back(mesh.point_index[std::size_t(triangle[c])]);
      }
      kept[c] = index;
    }
    cropped.triangles.push_back(kept);
  }
  return cropped;
}


}  // namespace hsmap
