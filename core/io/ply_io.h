#pragma once
// PLY meshes and point clouds (map/mesh.ply, map/sparse.ply, truth/scene.ply)
// through CGAL's PLY I/O; hsmap code sees only the plain PlyMesh below.
//
// writePly: through CGAL::Surface_mesh and CGAL::IO::write_PLY, binary little
// endian (default) or ASCII (17 significant digits, so doubles round-trip).
// Coordinates and normals are doubles; colours are the "v:color" map, which
// CGAL writes as uchar red, green, blue and alpha (alpha = 255). A point cloud
// is a mesh with no triangles (`element face 0`). The file is written under a
// temporary name and renamed when complete. Vertex order is kept; a triangle
// that would make the mesh non-manifold (which Surface_mesh cannot hold) is
// written on its own copies of its three vertices, so the geometry is kept
// and only the sharing of those vertices is lost. Triangles with an index
// out of range or a repeated index, or colour/normal counts that do not match
// the vertices, are std::invalid_argument.
//
// readPly: ASCII, binary little and binary big endian, through CGAL's
// polygon-soup read_PLY (CGAL's Surface_mesh reader is not used because it
// indexes with unchecked face indices and refuses non-manifold meshes). The
// header is checked first so that bad files are errors, not crashes or
// silent losses: vertex x, y, z must be float or double; colours, when
// present, uchar red, green, blue (alpha and any other property is ignored);
// normals nx, ny, nz float or double; face indices a list of int or uint.
// Faces with more than three vertices are triangulated as fans (v0, vi, vi+1),
// which is exact for the convex polygons PLY writers produce; faces with fewer
// than three vertices, repeated vertices or an index out of range are
// InputError naming the file and the face.

#include <cstdint>
#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace hsmap {

enum class PlyEncoding { binary, ascii };

struct PlyMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Matrix<std::uint8_t, 3, 1>> colors;  // empty or one per vertex
  std::vector<Eigen::Vector3i> triangles;                 // empty for a point cloud
  std::vector<Eigen::Vector3d> normals;                   // empty or one per vertex
};

void writePly(const std::filesystem::path& path, const PlyMesh& mesh,
              PlyEncoding encoding = PlyEncoding::binary);

PlyMesh readPly(const std::filesystem::path& path);

}  // namespace hsmap
