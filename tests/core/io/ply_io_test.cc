#include "core/io/ply_io.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/util/input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::TempFolder;
using Color = Eigen::Matrix<std::uint8_t, 3, 1>;

// A tetrahedron with awkward coordinates (not exact in decimal) and colours.
PlyMesh tetrahedron() {
  PlyMesh mesh;
  mesh.vertices = {{0.1, 0.2, 0.3}, {1.0 / 3.0, -2.5e-7, 4.0}, {123456.789, 7.0, -0.7}, {1e10, -1e-10, 2.0}};
  mesh.colors = {Color(255, 0, 0), Color(0, 255, 0), Color(0, 0, 255), Color(17, 34, 51)};
  mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return mesh;
}

// The same triangle read from any of its three starting vertices.
Eigen::Vector3i canonical(const Eigen::Vector3i& t) {
  int k = 0;
  if (t[1] < t[k]) k = 1;
  if (t[2] < t[k]) k = 2;
  return Eigen::Vector3i(t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
}

void expectSameTriangles(const std::vector<Eigen::Vector3i>& actual, const std::vector<Eigen::Vector3i>& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t f = 0; f < expected.size(); ++f) {
    EXPECT_EQ(canonical(actual[f]), canonical(expected[f])) << "triangle " << f;
  }
}

void expectSameMesh(const PlyMesh& actual, const PlyMesh& expected) {
  ASSERT_EQ(actual.vertices.size(), expected.vertices.size());
  for (std::size_t i = 0; i < expected.vertices.size(); ++i) {
    EXPECT_EQ(actual.vertices[i], expected.vertices[i]) << "vertex " << i;  // exact: doubles round-trip
  }
  EXPECT_EQ(actual.colors, expected.colors);
  EXPECT_EQ(actual.normals, expected.normals);
  expectSameTriangles(actual.triangles, expected.triangles);
}

TEST(PlyIo, BinaryRoundTripWithColoursAndFaces) {
  TempFolder dir;
  writePly(dir / "mesh.ply", tetrahedron());
  EXPECT_FALSE(std::filesystem::exists(dir / "mesh.ply.partial"));
  EXPECT_EQ(TempFolder::read(dir / "mesh.ply").rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
  expectSameMesh(readPly(dir / "mesh.ply"), tetrahedron());
}

TEST(PlyIo, AsciiRoundTripKeepsEveryDigit) {
  TempFolder dir;
  writePly(dir / "mesh.ply", tetrahedron(), PlyEncoding::ascii);
  EXPECT_EQ(TempFolder::read(dir / "mesh.ply").rfind("ply\nformat ascii 1.0\n", 0), 0u);
  expectSameMesh(readPly(dir / "mesh.ply"), tetrahedron());
}

TEST(PlyIo, PointCloudWithNormalsAndNoFaces) {
  TempFolder dir;
  PlyMesh cloud;
  cloud.vertices = {{1, 2, 3}, {4, 5, 6}, {-7, 8.5, 9}};
  cloud.normals = {{0, 0, 1}, {0, 0.6, 0.8}, {-1, 0, 0}};
  writePly(dir / "sparse.ply", cloud);
  expectSameMesh(readPly(dir / "sparse.ply"), cloud);
}

TEST(PlyIo, NonManifoldTriangleIsWrittenOnItsOwnVertices) {
  TempFolder dir;
  PlyMesh fan;  // three triangles on the edge 0-1: Surface_mesh cannot hold the third
  fan.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  fan.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  writePly(dir / "fan.ply", fan, PlyEncoding::ascii);
  const PlyMesh back = readPly(dir / "fan.ply");
  ASSERT_EQ(back.vertices.size(), 8u);
  ASSERT_EQ(back.triangles.size(), 3u);
  for (std::size_t f = 0; f < 3; ++f) {
    // Same corners, in the same cyclic order.
    std::vector<Eigen::Vector3d> written, read;
    for (int k = 0; k < 3; ++k) {
      written.push_back(fan.vertices[fan.triangles[f][k]]);
      read.push_back(back.vertices[back.triangles[f][k]]);
    }
    const auto start = std::find(read.begin(), read.end(), written[0]);
    ASSERT_NE(start, read.end()) << "triangle " << f;
    std::rotate(read.begin(), start, read.end());
    EXPECT_EQ(read, written) << "triangle " << f;
  }
}

TEST(PlyIo, WriterRejectsInconsistentMeshes) {
  TempFolder dir;
  PlyMesh mesh = tetrahedron();
  mesh.triangles.push_back({0, 1, 4});
  EXPECT_THROW(writePly(dir / "bad.ply", mesh), std::invalid_argument);
  mesh = tetrahedron();
  mesh.triangles.push_back({0, 1, 1});
  EXPECT_THROW(writePly(dir / "bad.ply", mesh), std::invalid_argument);
  mesh = tetrahedron();
  mesh.colors.pop_back();
  EXPECT_THROW(writePly(dir / "bad.ply", mesh), std::invalid_argument);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

// Written by hand as another tool would: float coordinates, an extra
// property, a comment, a quad (triangulated as a fan) and a triangle.
TEST(PlyIo, ReadsAHandWrittenAsciiFileWithAQuad) {
  TempFolder dir;
  const auto path = dir.write("hand.ply",
                              "ply\n"
                              "format ascii 1.0\n"
                              "comment written by hand\n"
                              "element vertex 5\n"
                              "property float x\n"
                              "property float y\n"
                              "property float z\n"
                              "property float quality\n"
                              "property uchar red\n"
                              "property uchar green\n"
                              "property uchar blue\n"
                              "element face 2\n"
                              "property list uchar int vertex_indices\n"
                              "end_header\n"
                              "0 0 0 0.5 10 20 30\n"
                              "1 0 0 0.5 40 50 60\n"
                              "1 1 0 0.5 70 80 90\n"
                              "0 1 0 0.5 100 110 120\n"
                              "0.5 0.5 1.25 0.5 130 140 150\n"
                              "4 0 1 2 3\n"
                              "3 0 1 4\n");
  const PlyMesh mesh = readPly(path);
  ASSERT_EQ(mesh.vertices.size(), 5u);
  EXPECT_EQ(mesh.vertices[4], Eigen::Vector3d(0.5, 0.5, 1.25));
  ASSERT_EQ(mesh.colors.size(), 5u);
  EXPECT_EQ(mesh.colors[3], Color(100, 110, 120));
  EXPECT_TRUE(mesh.normals.empty());
  const std::vector<Eigen::Vector3i> expected{{0, 1, 2}, {0, 2, 3}, {0, 1, 4}};
  EXPECT_EQ(mesh.triangles, expected);
}

// Binary big endian, assembled byte by byte.
TEST(PlyIo, ReadsBinaryBigEndian) {
  TempFolder dir;
  std::string bytes =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
      "property double z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n";
  const auto appendBigEndian = [&bytes](const void* value, std::size_t size) {
    const auto* p = static_cast<const char*>(value);
    for (std::size_t k = 0; k < size; ++k) bytes += p[size - 1 - k];  // this host is little endian
  };
  const double coordinates[9] = {0.1, 0.2, 0.3, 1.5, 0, 0, 0, -2.25, 1e-9};
  for (const double c : coordinates) appendBigEndian(&c, sizeof c);
  bytes += static_cast<char>(3);
  for (const std::uint32_t index : {2u, 0u, 1u}) appendBigEndian(&index, sizeof index);
  const PlyMesh mesh = readPly(dir.write("be.ply", bytes));
  ASSERT_EQ(mesh.vertices.size(), 3u);
  EXPECT_EQ(mesh.vertices[0], Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(mesh.vertices[2], Eigen::Vector3d(0, -2.25, 1e-9));
  EXPECT_EQ(mesh.triangles, (std::vector<Eigen::Vector3i>{{2, 0, 1}}));
}

std::string errorOf(const std::filesystem::path& path) {
  try {
    readPly(path);
  } catch (const InputError& error) {
    return error.what();
  }
  return "no error";
}

constexpr const char* kAsciiHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";

TEST(PlyIo, MalformedFilesAreInputErrors) {
  TempFolder dir;
  const auto check = [&](const std::string& name, const std::string& content, const std::string& expected) {
    const auto path = dir.write(name, content);
    EXPECT_EQ(errorOf(path), path.string() + expected) << name;
  };
  check("not.ply", "OFF\n3 1 0\n",
        ": not a PLY file: expected 'ply' on line 1 and "
        "'format ascii|binary_little_endian|binary_big_endian 1.0' on line 2");
  check("range.ply", std::string(kAsciiHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
        ":element face 0: vertex index 7 out of range (the file has 3 vertices)");
  check("negative.ply", std::string(kAsciiHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n",
        ":element face 0: vertex index 18446744073709551615 out of range (the file has 3 vertices)");
  check("short_face.ply", std::string(kAsciiHeader) + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
        ":element face 0: expected at least 3 vertices, found 2");
  check("repeat.ply", std::string(kAsciiHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 1\n",
        ":element face 0: a vertex index is repeated");
  check("early_end.ply", std::string(kAsciiHeader) + "0 0 0\n1 0 0\n",
        ": malformed PLY data: the values do not match the header (data ends early or is not a number)");
  check("not_number.ply", std::string(kAsciiHeader) + "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n",
        ": malformed PLY data: the values do not match the header (data ends early or is not a number)");
  check("int_x.ply",
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty int x\nproperty int y\nproperty int z\nend_header\n1 2 3\n",
        ":element vertex: property x: expected float or double");
  check("two_colours.ply",
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
        "property uchar red\nproperty uchar green\nend_header\n1 2 3 4 5\n",
        ":element vertex: expected all of red, green and blue, or none");
  check("no_vertex.ply", "ply\nformat ascii 1.0\nend_header\n", ": expected a vertex element");
  EXPECT_EQ(errorOf(dir / "absent.ply"), (dir / "absent.ply").string() + ": file not found");

  // A binary file cut short.
  writePly(dir / "whole.ply", tetrahedron());
  const std::string whole = TempFolder::read(dir / "whole.ply");
  check("cut.ply", whole.substr(0, whole.size() - 5),
        ": malformed PLY data: the values do not match the header (data ends early or is not a number)");
}

}  // namespace
}  // namespace hsmap
