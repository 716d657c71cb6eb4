#pragma once
// A regular height-field mesh for the ray-caster tests: vertices on an
// nx x ny grid of spacing h at (x0 + i h, y0 + j h, depth(x, y)), each cell
// split along its (i, j)-(i+1, j+1) diagonal into two triangles.

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <vector>

namespace hsmap::test {

struct HeightField {
  double x0 = 0.0, y0 = 0.0, h = 0.1;
  int nx = 0, ny = 0;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;

  int vertex(int i, int j) const { return i * ny + j; }

  // The triangle whose plan view contains (x, y): cell (i, j) holds triangles
  // 2 c (below the diagonal, local fy <= fx) and 2 c + 1, c = i (ny - 1) + j.
  // Returns -1 outside the grid or within `margin` (in cell units) of a cell
  // edge or the diagonal, where either neighbour may be hit.
  int triangleUnder(double x, double y, double margin) const {
    const double gx = (x - x0) / h, gy = (y - y0) / h;
    const double i = std::floor(gx), j = std::floor(gy);
    if (i < 0 || j < 0 || i >= nx - 1 || j >= ny - 1) return -1;
    const double fx = gx - i, fy = gy - j;
    if (fx < margin || fx > 1 - margin || fy < margin || fy > 1 - margin ||
        std::abs(fx - fy) < margin) {
      return -1;
    }
    const int cell = static_cast<int>(i) * (ny - 1) + static_cast<int>(j);
    return 2 * cell + (fy <= fx ? 0 : 1);
  }
};

inline HeightField makeHeightField(int nx, int ny, double h, double x0, double y0,
                                   const std::function<double(double, double)>& depth) {
  HeightField field;
  field.x0 = x0;
  field.y0 = y0;
  field.h = h;
  field.nx = nx;
  field.ny = ny;
  field.vertices.reserve(static_cast<std::size_t>(nx) * ny);
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      const double x = x0 + i * h, y = y0 + j * h;
      field.vertices.emplace_back(x, y, depth(x, y));
    }
  }
  for (int i = 0; i + 1 < nx; ++i) {
    for (int j = 0; j + 1 < ny; ++j) {
      const int a = field.vertex(i, j), b = field.vertex(i + 1, j);
      const int c = field.vertex(i + 1, j + 1), d = field.vertex(i, j + 1);
      field.triangles.emplace_back(a, b, c);
      field.triangles.emplace_back(a, c, d);
    }
  }
  return field;
}

}  // namespace hsmap::test
