#include "core/io/ply_io.h"

#include <CGAL/IO/Color.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/IO/read_ply_points.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/property_map.h>

#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/io/atomic_file.h"
#include "core/util/input_error.h"
#include "core/util/regular_file.h"

namespace hsmap {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Color = CGAL::IO::Color;

// Polygons are small (triangles, mostly): a pairwise check, without the
// allocation a std::set per face costs (1.5 M faces on a long survey).
bool hasRepeatedIndex(const std::vector<std::size_t>& polygon) {
  for (std::size_t i = 0; i < polygon.size(); ++i)
    for (std::size_t j = i + 1; j < polygon.size(); ++j)
      if (polygon[i] == polygon[j]) return true;
  return false;
}

void checkMesh(const PlyMesh& mesh, const std::filesystem::path& path) {
  const std::size_t n = mesh.vertices.size();
  const auto fail = [&](const std::string& what) {
    throw std::invalid_argument("writePly " + path.string() + ": " + what);
  };
  if (!mesh.colors.empty() && mesh.colors.size() != n) {
    fail(std::to_string(mesh.colors.size()) + " colours for " + std::to_string(n) + " vertices");
  }
  if (!mesh.normals.empty() && mesh.normals.size() != n) {
    fail(std::to_string(mesh.normals.size()) + " normals for " + std::to_string(n) + " vertices");
  }
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Eigen::Vector3i& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || static_cast<std::size_t>(t[k]) >= n) {
        fail("triangle " + std::to_string(f) + " has vertex index " + std::to_string(t[k]) +
             " outside [0, " + std::to_string(n) + ")");
      }
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      fail("triangle " + std::to_string(f) + " repeats a vertex");
    }
  }
}

// What the header of a PLY file declares, checked against what readPly can
// take, using CGAL's own header parser.
struct PlyLayout {
  bool has_normals = false;
};

template <typename T>
bool isA(CGAL::IO::internal::PLY_read_number* property) {
  return dynamic_cast<CGAL::IO::internal::PLY_read_typed_number<T>*>(property) != nullptr;
}

template <typename T>
bool isListOf(CGAL::IO::internal::PLY_read_number* property) {
  return dynamic_cast<CGAL::IO::internal::PLY_read_typed_list<T>*>(property) != nullptr;
}

PlyLayout checkHeader(const std::filesystem::path& path) {
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw InputError(path, "", "cannot open for reading");
  CGAL::IO::internal::PLY_reader reader(false);
  if (!reader.init(stream)) {
    throw InputError(path, "", "not a PLY file: expected 'ply' on line 1 and "
                               "'format ascii|binary_little_endian|binary_big_endian 1.0' on line 2");
  }
  PlyLayout layout;
  bool has_vertices = false;
  for (std::size_t e = 0; e < reader.number_of_elements(); ++e) {
    CGAL::IO::internal::PLY_element& element = reader.element(e);
    const std::string& name = element.name();
    if (name == "vertex" || name == "vertices") {
      has_vertices = true;
      int coordinates = 0, colours = 0, normals = 0;
      for (std::size_t k = 0; k < element.number_of_properties(); ++k) {
        auto* property = element.property(k);
        const std::string& p = property->name();
        const bool real = isA<float>(property) || isA<double>(property);
        if (p == "x" || p == "y" || p == "z") {
          if (!real) throw InputError(path, "element " + name, "property " + p + ": expected float or double");
          ++coordinates;
        } else if (p == "nx" || p == "ny" || p == "nz") {
          if (!real) throw InputError(path, "element " + name, "property " + p + ": expected float or double");
          ++normals;
        } else if (p == "red" || p == "green" || p == "blue") {
          if (!isA<std::uint8_t>(property)) {
            throw InputError(path, "element " + name, "property " + p + ": expected uchar colour");
          }
          ++colours;
        }
      }
      if (coordinates != 3) throw InputError(path, "element " + name, "expected properties x, y and z");
      if (colours != 0 && colours != 3) {
        throw InputError(path, "element " + name, "expected all of red, green and blue, or none");
      }
      if (normals != 0 && normals != 3) {
        throw InputError(path, "element " + name, "expected all of nx, ny and nz, or none");
      }
      layout.has_normals = normals == 3;
    } else if (name == "face" || name == "faces") {
      bool has_indices = false;
      for (std::size_t k = 0; k < element.number_of_properties(); ++k) {
        auto* property = element.property(k);
        if (property->name() != "vertex_indices" && property->name() != "vertex_index") continue;
        if (!isListOf<std::int32_t>(property) && !isListOf<std::uint32_t>(property)) {
          throw InputError(path, "element " + name,
                           "property " + property->name() + ": expected a list of int or uint");
        }
        has_indices = true;
      }
      if (!has_indices) {
        throw InputError(path, "element " + name, "expected a vertex_indices list property");
      }
    }
  }
  if (!has_vertices) throw InputError(path, "", "expected a vertex element");
  return layout;
}

}  // namespace

void writePly(const std::filesystem::path& path, const PlyMesh& mesh, PlyEncoding encoding) {
  checkMesh(mesh, path);
  Mesh sm;
  sm.reserve(mesh.vertices.size(), 3 * mesh.triangles.size() / 2, mesh.triangles.size());
  for (const Eigen::Vector3d& v : mesh.vertices) sm.add_vertex(Point(v.x(), v.y(), v.z()));
  Mesh::Property_map<Mesh::Vertex_index, Color> colors;
  Mesh::Property_map<Mesh::Vertex_index, Vector> normals;
  if (!mesh.colors.empty()) colors = sm.add_property_map<Mesh::Vertex_index, Color>("v:color").first;
  if (!mesh.normals.empty()) normals = sm.add_property_map<Mesh::Vertex_index, Vector>("v:normal").first;
  const auto setAttributes = [&](Mesh::Vertex_index v, std::size_t source) {
    if (!mesh.colors.empty()) {
      const auto& c = mesh.colors[source];
      colors[v] = Color(c[0], c[1], c[2]);
    }
    if (!mesh.normals.empty()) {
      const Eigen::Vector3d& n = mesh.normals[source];
      normals[v] = Vector(n.x(), n.y(), n.z());
    }
  };
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) setAttributes(Mesh::Vertex_index(static_cast<Mesh::size_type>(i)), i);

  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Mesh::Vertex_index a(t[0]), b(t[1]), c(t[2]);
    if (sm.add_face(a, b, c) != Mesh::null_face()) continue;
    // Non-manifold here: give the triangle its own vertices (see header).
    Mesh::Vertex_index copies[3];
    for (int k = 0; k < 3; ++k) {
      // A copy: add_vertex may reallocate the storage sm.point refers to.
      const Point corner = sm.point(Mesh::Vertex_index(t[k]));
      copies[k] = sm.add_vertex(corner);
      setAttributes(copies[k], static_cast<std::size_t>(t[k]));
    }
    if (sm.add_face(copies[0], copies[1], copies[2]) == Mesh::null_face()) {
      throw std::logic_error("writePly: CGAL refused an isolated triangle");
    }
  }

  AtomicFile file(path);
  std::ofstream& stream = file.stream();
  CGAL::IO::set_mode(stream, encoding == PlyEncoding::binary ? CGAL::IO::BINARY : CGAL::IO::ASCII);
  const bool written = CGAL::IO::write_PLY(stream, sm, CGAL::parameters::stream_precision(17));
  if (!written) throw std::runtime_error("writing " + path.string() + " failed in CGAL::IO::write_PLY");
  file.commit();
}

PlyMesh readPly(const std::filesystem::path& path) {
  // A FIFO or a device is an error before any stream blocks on it or reads
  // it without end.
  { const RegularFile check(path); }
  const PlyLayout layout = checkHeader(path);

  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  std::vector<Color> face_colors, vertex_colors;
  {
    std::ifstream stream(path, std::ios::binary);
    bool read = false;
    try {
      read = CGAL::IO::read_PLY(stream, points, polygons, face_colors, vertex_colors, false);
    } catch (const std::bad_alloc&) {
      read = false;  // a corrupt list length asked for an absurd allocation
    }
    if (!read) {
      throw InputError(path, "", "malformed PLY data: the values do not match the header "
                                 "(data ends early or is not a number)");
    }
  }

  PlyMesh mesh;
  mesh.vertices.reserve(points.size());
  for (const Point& p : points) mesh.vertices.emplace_back(p.x(), p.y(), p.z());
  if (!vertex_colors.empty()) {
    if (vertex_colors.size() != points.size()) {
      throw InputError(path, "element vertex", "read " + std::to_string(vertex_colors.size()) +
                                                   " colours for " + std::to_string(points.size()) + " vertices");
    }
    mesh.colors.reserve(vertex_colors.size());
    for (const Color& c : vertex_colors) mesh.colors.emplace_back(c.red(), c.green(), c.blue());
  }
  const std::size_t n = points.size();
  mesh.triangles.reserve(polygons.size());
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    const std::vector<std::size_t>& polygon = polygons[f];
    // Named only on error: a string per face costs more than the checks.
    const auto where = [f] { return "element face " + std::to_string(f); };
    if (polygon.size() < 3) {
      throw InputError(path, where(), "expected at least 3 vertices, found " + std::to_string(polygon.size()));
    }
    for (const std::size_t index : polygon) {
      // uint lists may hold values that do not fit an int index.
      if (index >= n || index > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
        throw InputError(path, where(), "vertex index " + std::to_string(index) + " out of range (the file has " +
                                          std::to_string(n) + " vertices)");
      }
    }
    if (hasRepeatedIndex(polygon)) {
      throw InputError(path, where(), "a vertex index is repeated");
    }
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
      mesh.triangles.emplace_back(static_cast<int>(polygon[0]), static_cast<int>(polygon[k]),
                                  static_cast<int>(polygon[k + 1]));
    }
  }
  if (layout.has_normals) {
    std::ifstream stream(path, std::ios::binary);
    std::vector<Vector> normals;
    const bool read = CGAL::IO::read_PLY_with_properties(
        stream, std::back_inserter(normals),
        CGAL::IO::make_ply_normal_reader(CGAL::Identity_property_map<Vector>()));
    if (!read || normals.size() != n) {
      throw InputError(path, "element vertex", "could not read the normals nx, ny, nz");
    }
    mesh.normals.reserve(n);
    for (const Vector& v : normals) mesh.normals.emplace_back(v.x(), v.y(), v.z());
  }
  return mesh;
}

}  // namespace hsmap
