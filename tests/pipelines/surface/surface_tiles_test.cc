// The dense surface's tiles: every triangle lands in exactly one tile, every
// depth a reference can give is inside the padded squares of the tiles that
// list it, and tiles come in the order the vehicle reaches them.
#include "pipelines/surface/surface_tiles.h"

#include <gtest/gtest.h>

#include <random>

namespace hsmap {
namespace {

PinholeRadtanCamera surveyCamera() {
  PinholeRadtanParameters p;
  p.width = 960;
  p.height = 540;
  p.fx = p.fy = 800;
  p.cx = 480.3;
  p.cy = 268.4;
  p.distortion = {-0.08, 0.02, 4e-4, -3e-4, 0};
  return PinholeRadtanCamera(p);
}

// Keyframes looking down (camera z along W's z, NED: down) at 2 m, along a
// diagonal track, each its own reference with depths 1.7..2.3 m.
struct DiagonalTrack {
  VisualMap map;
  std::vector<std::optional<StereoPartner>> partners;
};

DiagonalTrack diagonalTrack(int count) {
  DiagonalTrack track;
  for (int k = 0; k < count; ++k) {
    SE3d T_W_C;
    T_W_C.q = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()));
    T_W_C.t = Eigen::Vector3d(0.3 * k, 0.2 * k - 5.0, -2.0);
    track.map.addKeyframe(k, 0.1 * k, 0, T_W_C);
    StereoPartner partner;
    partner.keyframe = k;
    partner.partner = k + 1 < count ? k + 1 : k - 1;
    partner.min_depth_m = 1.7;
    partner.max_depth_m = 2.3;
    partner.median_depth_m = 2.0;
    track.partners.push_back(partner);
  }
  return track;
}

TEST(SurfaceTiles, EveryDepthAReferenceCanGiveIsInTheTilesThatListIt) {
  const DiagonalTrack track = diagonalTrack(40);
  const PinholeRadtanCamera camera = surveyCamera();
  const double size = 2.0, margin = 0.3;
  const auto tiles = layOutTiles(track.map, track.partners, camera, size, margin);
  ASSERT_FALSE(tiles.empty());
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(0.0, camera.width() - 1.0), v(0.0, camera.height() - 1.0),
      z(1.7, 2.3);
  for (const Keyframe& keyframe : track.map.keyframes()) {
    for (int sample = 0; sample < 200; ++sample) {
      const auto ray = camera.unproject({u(random), v(random)});
      ASSERT_TRUE(ray);
      const Eigen::Vector3d p_W = keyframe.T_F_C * Eigen::Vector3d(*ray * (z(random) / ray->z()));
      // The tile whose square holds p lists the keyframe, and so does every
      // tile whose padded square holds it.
      int owners = 0;
      for (const SurfaceTile& tile : tiles) {
        const bool listed = std::binary_search(tile.keyframes.begin(), tile.keyframes.end(), keyframe.id);
        if (inHalfOpen(tile.core, p_W.head<2>())) {
          ++owners;
          EXPECT_TRUE(listed) << "keyframe " << keyframe.id;
        }
        if (tile.padded.contains(p_W.head<2>())) EXPECT_TRUE(listed) << "keyframe " << keyframe.id;
      }
      EXPECT_EQ(owners, 1);
    }
  }
  // In the order the vehicle reaches them.
  for (std::size_t t = 1; t < tiles.size(); ++t) {
    EXPECT_LE(tiles[t - 1].keyframes.front(), tiles[t].keyframes.front());
  }
  // Squares of the grid anchored at W's origin, margins around them.
  for (const SurfaceTile& tile : tiles) {
    EXPECT_NEAR(std::remainder(tile.core.min().x(), size), 0.0, 1e-12);
    EXPECT_NEAR(tile.core.sizes().x(), size, 1e-12);
    EXPECT_NEAR(tile.padded.sizes().y(), size + 2 * margin, 1e-12);
  }
}

TEST(SurfaceTiles, KeyframesWithoutAPartnerAreNotInAnyTile) {
  DiagonalTrack track = diagonalTrack(10);
  track.partners[3].reset();
  for (const SurfaceTile& tile : layOutTiles(track.map, track.partners, surveyCamera(), 2.0, 0.3)) {
    EXPECT_FALSE(std::binary_search(tile.keyframes.begin(), tile.keyframes.end(), 3));
  }
}

TEST(SurfaceTiles, CroppingPartitionsTheTrianglesAndKeepsPointIndices) {
  // A random triangle soup over 5 m x 5 m; every triangle in exactly one of
  // the tiles of a 1 m grid, with its vertices and their point indices.
  std::mt19937 random(3);
  std::uniform_real_distribution<double> coordinate(-2.5, 2.5);
  SurfaceMesh mesh;
  for (int i = 0; i < 3000; ++i) {
    mesh.vertices.emplace_back(coordinate(random), coordinate(random), 0.1 * coordinate(random));
    mesh.point_index.push_back(1000 + i);
  }
  std::uniform_int_distribution<int> vertex(0, 2999);
  for (int i = 0; i < 4000; ++i) mesh.triangles.emplace_back(vertex(random), vertex(random), vertex(random));
  std::size_t kept = 0;
  for (int ix = -3; ix < 3; ++ix) {
    for (int iy = -3; iy < 3; ++iy) {
      const Eigen::AlignedBox2d core(Eigen::Vector2d(ix, iy), Eigen::Vector2d(ix + 1, iy + 1));
      const SurfaceMesh cropped = cropToTile(mesh, core);
      kept += cropped.triangles.size();
      ASSERT_EQ(cropped.point_index.size(), cropped.vertices.size());
      for (const Eigen::Vector3i& triangle : cropped.triangles) {
        const Eigen::Vector3d centroid = (cropped.vertices[std::size_t(triangle[0])] +
                                          cropped.vertices[std::size_t(triangle[1])] +
                                          cropped.vertices[std::size_t(triangle[2])]) / 3.0;
        EXPECT_TRUE(inHalfOpen(core, centroid.head<2>()));
      }
      for (std::size_t v = 0; v < cropped.vertices.size(); ++v) {
        const int original = cropped.point_index[v] - 1000;
        EXPECT_EQ(cropped.vertices[v], mesh.vertices[std::size_t(original)]);
      }
    }
  }
  EXPECT_EQ(kept, mesh.triangles.size());
}

}  // namespace
}  // namespace hsmap
