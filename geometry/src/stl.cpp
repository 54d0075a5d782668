// STL reading and writing. STL stores float32 coordinates and repeats every shared corner, so
// vertices are welded by their exact float32 bits (a weld tolerance would join distinct corners
// of fine meshes).
#include "shard/geometry/stl.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unordered_map>

namespace shard::geometry {
namespace {

struct FloatKey {
  std::uint32_t x, y, z;
  bool operator==(const FloatKey&) const = default;
};

struct FloatKeyHash {
  std::size_t operator()(const FloatKey& k) const {
    std::uint64_t h = k.x;
    h = h * 0x9E3779B97F4A7C15ULL ^ k.y;
    h = h * 0x9E3779B97F4A7C15ULL ^ k.z;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

// -0.0f and 0.0f are the same point.
std::uint32_t bits_of(float value) { return std::bit_cast<std::uint32_t>(value == 0.0f ? 0.0f : value); }

class MeshBuilder {
 public:
  explicit MeshBuilder(double scale) : scale_(scale) {}

  void add_triangle(const std::array<float, 9>& corners) {
    std::array<Index, 3> face{};
    for (int c = 0; c < 3; ++c) face[c] = vertex(corners[3 * c], corners[3 * c + 1], corners[3 * c + 2]);
    ++triangles_read_;
    if (face[0] == face[1] || face[1] == face[2] || face[0] == face[2]) return;
    mesh_.faces.push_back(face);
  }
  std::size_t triangles_read() const { return triangles_read_; }
  TriangleMesh take() { return std::move(mesh_); }

 private:
  Index vertex(float x, float y, float z) {
    const FloatKey key{bits_of(x), bits_of(y), bits_of(z)};
    auto [it, inserted] = index_.try_emplace(key, static_cast<Index>(mesh_.vertices.size()));
    if (inserted) mesh_.vertices.emplace_back(scale_ * x, scale_ * y, scale_ * z);
    return it->second;
  }

  double scale_;
  TriangleMesh mesh_;
  std::unordered_map<FloatKey, Index, FloatKeyHash> index_;
  std::size_t triangles_read_ = 0;
};

std::string read_all(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec))
    throw StlError(fmt::format("STL file '{}' does not exist: check the path (relative paths are "
                               "resolved against the scene folder)",
                               file.string()));
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw StlError(fmt::format("STL file '{}' cannot be opened: check its permissions", file.string()));
  std::ostringstream content;
  content << in.rdbuf();
  return content.str();
}

bool looks_binary(const std::string& bytes) {
  if (bytes.size() < 84) return false;
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, sizeof count);
  // Binary writers sometimes start the header with "solid" too; the size test decides.
  return bytes.size() == 84 + 50 * static_cast<std::uint64_t>(count);
}

void parse_binary(const std::string& bytes, MeshBuilder& builder) {
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, sizeof count);
  for (std::uint32_t t = 0; t < count; ++t) {
    std::array<float, 9> corners{};
    // 12 bytes normal (ignored: orientation comes from the vertex order), 36 bytes corners.
    std::memcpy(corners.data(), bytes.data() + 84 + 50 * static_cast<std::size_t>(t) + 12, sizeof corners);
    builder.add_triangle(corners);
  }
}

void parse_ascii(const std::string& text, const std::filesystem::path& file, MeshBuilder& builder) {
  std::istringstream in(text);
  std::string word;
  std::array<float, 9> corners{};
  int corner = 0;
  std::size_t line_guess = 0;
  while (in >> word) {
    if (word == "vertex") {
      double x = 0, y = 0, z = 0;
      if (!(in >> x >> y >> z) || corner >= 3)
        throw StlError(fmt::format("STL file '{}' is malformed near facet {}: a 'vertex' line needs "
                                   "three numbers and a facet three vertices; re-export the file",
                                   file.string(), line_guess + 1));
      // STL stores float32: rounding here makes ASCII and binary copies of a shape identical.
      corners[3 * corner] = static_cast<float>(x);
      corners[3 * corner + 1] = static_cast<float>(y);
      corners[3 * corner + 2] = static_cast<float>(z);
      ++corner;
    } else if (word == "endloop") {
      if (corner != 3)
        throw StlError(fmt::format("STL file '{}': facet {} has {} vertices instead of 3; export "
                                   "a triangulated surface",
                                   file.string(), line_guess + 1, corner));
      builder.add_triangle(corners);
      corner = 0;
      ++line_guess;
    }
  }
  if (corner != 0)
    throw StlError(fmt::format("STL file '{}' ends inside a facet: the file is truncated; re-export it",
                               file.string()));
}

}  // namespace

TriangleMesh read_stl(const std::filesystem::path& file, double scale) {
  if (!(scale > 0.0))
    throw StlError(fmt::format("STL file '{}': scale must be > 0 (got {}); use 0.001 for a file in mm",
                               file.string(), scale));
  const std::string bytes = read_all(file);
  MeshBuilder builder(scale);
  if (looks_binary(bytes)) {
    parse_binary(bytes, builder);
  } else if (bytes.compare(0, 5, "solid") == 0 || bytes.find("facet") != std::string::npos) {
    parse_ascii(bytes, file, builder);
  } else if (bytes.empty()) {
    throw StlError(fmt::format("STL file '{}' is empty (0 bytes): export the body again", file.string()));
  } else {
    throw StlError(fmt::format("STL file '{}' is neither ASCII STL (no 'solid'/'facet') nor binary STL "
                               "(size {} bytes does not match 84 + 50 x triangle count): the file is "
                               "truncated or not an STL",
                               file.string(), bytes.size()));
  }
  TriangleMesh mesh = builder.take();
  // A NaN or infinite coordinate (a corrupt float in a binary file, "nan" in an ASCII one) would
  // poison every later test (found by fuzzing: tests/fuzz/fuzz_stl.cpp).
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    if (!mesh.vertices[v].allFinite())
      throw StlError(fmt::format("STL file '{}': vertex {} has a non-finite coordinate (NaN or infinity): the "
                                 "file is corrupt; export the body again",
                                 file.string(), v));
  if (mesh.faces.empty())
    throw StlError(fmt::format("STL file '{}' contains no triangles ({} degenerate ones read): export "
                               "the body as a triangulated surface",
                               file.string(), builder.triangles_read()));
  return mesh;
}

void write_stl(const std::filesystem::path& file, const TriangleMesh& mesh, StlFormat format,
               const std::string& name) {
  std::ofstream out(file, std::ios::binary);
  if (!out) throw StlError(fmt::format("cannot write STL file '{}': check the folder exists", file.string()));
  auto normal_of = [&](const std::array<Index, 3>& f) {
    const Vec3 n = (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]);
    const double len = n.norm();
    return len > 0 ? Vec3(n / len) : Vec3::Zero();
  };
  if (format == StlFormat::Binary) {
    std::array<char, 80> header{};
    std::memcpy(header.data(), name.data(), std::min<std::size_t>(name.size(), 79));
    out.write(header.data(), header.size());
    const auto count = static_cast<std::uint32_t>(mesh.faces.size());
    out.write(reinterpret_cast<const char*>(&count), sizeof count);
    for (const auto& f : mesh.faces) {
      std::array<float, 12> record{};
      const Vec3 n = normal_of(f);
      for (int k = 0; k < 3; ++k) record[k] = static_cast<float>(n[k]);
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) record[3 + 3 * c + k] = static_cast<float>(mesh.vertices[f[c]][k]);
      out.write(reinterpret_cast<const char*>(record.data()), sizeof record);
      const std::uint16_t attributes = 0;
      out.write(reinterpret_cast<const char*>(&attributes), sizeof attributes);
    }
  } else {
    out << "solid " << name << '\n';
    for (const auto& f : mesh.faces) {
      const Vec3 n = normal_of(f);
      out << fmt::format("  facet normal {:.9g} {:.9g} {:.9g}\n    outer loop\n", n.x(), n.y(), n.z());
      for (int c = 0; c < 3; ++c) {
        const Vec3& v = mesh.vertices[f[c]];
        // 9 significant digits reproduce a float32 exactly.
        out << fmt::format("      vertex {:.9g} {:.9g} {:.9g}\n", static_cast<float>(v.x()),
                           static_cast<float>(v.y()), static_cast<float>(v.z()));
      }
      out << "    endloop\n  endfacet\n";
    }
    out << "endsolid " << name << '\n';
  }
  if (!out) throw StlError(fmt::format("writing STL file '{}' failed (disk full?)", file.string()));
}

}  // namespace shard::geometry
