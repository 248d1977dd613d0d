#include <unexmin/sim/ply_reader.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace unexmin {
namespace sim {
namespace {

/// Bytes of a PLY scalar type by name (both spellings); 0 for an unknown name.
std::size_t typeSize(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8")
    return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16")
    return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" || type == "float32")
    return 4;
  if (type == "double" || type == "float64")
    return 8;
  return 0;
}

bool isFloat(const std::string& type) {
  return type == "float" || type == "float32";
}
bool isDouble(const std::string& type) {
  return type == "double" || type == "float64";
}
bool isUchar(const std::string& type) {
  return type == "uchar" || type == "uint8";
}
bool isIndex(const std::string& type) {
  return type == "int" || type == "int32" || type == "uint" || type == "uint32";
}

/// What the header says, for the layout this reader takes.
struct Layout {
  std::size_t vertices = 0, faces = 0;
  std::size_t vertex_bytes = 0;    // one vertex record
  std::size_t xyz[3] = {0, 0, 0};  // offsets in the record
  bool xyz_double = false;         // x, y, z are doubles (else floats)
  bool signed_index = true;        // the face indices are int (else uint)
  long rgb[3] = {-1, -1, -1};      // offsets of uchar red, green, blue; -1: absent
  std::size_t count_bytes = 0;     // the face list's count
};

/// Parses the header of `f` (at its start); false when the file is not of the layout this reader takes.
bool readHeader(std::FILE* f, Layout& layout) {
  char line[1024];
  if (!std::fgets(line, sizeof line, f) || std::strncmp(line, "ply", 3) != 0)
    return false;
  enum { none, vertex, face } element = none;
  bool seen_x = false, seen_y = false, seen_z = false, face_list = false, format = false;
  int elements = 0;
  std::string xyz_type;
  while (std::fgets(line, sizeof line, f)) {
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "end_header") {
      const bool rgb = layout.rgb[0] >= 0 && layout.rgb[1] >= 0 && layout.rgb[2] >= 0;
      const bool no_rgb = layout.rgb[0] < 0 && layout.rgb[1] < 0 && layout.rgb[2] < 0;
      return format && elements == 2 && seen_x && seen_y && seen_z && face_list && (rgb || no_rgb);
    }
    if (word == "format") {
      std::string name;
      words >> name;
      if (name != "binary_little_endian")
        return false;
      format = true;
    } else if (word == "element") {
      std::string name;
      std::size_t count = 0;
      words >> name >> count;
      if (elements == 0 && name == "vertex") {
        element = vertex;
        layout.vertices = count;
      } else if (elements == 1 && name == "face") {
        element = face;
        layout.faces = count;
      } else {
        return false;  // another element, or these two in another order
      }
      ++elements;
    } else if (word == "property") {
      std::string type, name;
      words >> type;
      if (element == vertex) {
        words >> name;
        const std::size_t size = typeSize(type);
        if (size == 0)
          return false;  // a list, or an unknown type
        const std::size_t at = layout.vertex_bytes;
        layout.vertex_bytes += size;
        if (name == "x" || name == "y" || name == "z") {
          if (!(isFloat(type) || isDouble(type)) || (!xyz_type.empty() && type != xyz_type))
            return false;
          xyz_type = type;
          layout.xyz_double = isDouble(type);
          const int k = name[0] - 'x';
          layout.xyz[k] = at;
          (k == 0 ? seen_x : k == 1 ? seen_y : seen_z) = true;
        } else if (name == "red" || name == "green" || name == "blue") {
          if (!isUchar(type))
            return false;
          layout.rgb[name == "red" ? 0 : name == "green" ? 1 : 2] = static_cast<long>(at);
        } else if (name != "nx" && name != "ny" && name != "nz" && name != "alpha") {
          return false;  // texture coordinates and anything else: assimp's reading
        }
      } else if (element == face) {
        std::string count_type, index_type;
        words >> count_type >> index_type >> name;
        if (type != "list" || face_list || (name != "vertex_indices" && name != "vertex_index") ||
            typeSize(count_type) == 0 || isFloat(count_type) || isDouble(count_type) || !isIndex(index_type))
          return false;
        layout.count_bytes = typeSize(count_type);
        layout.signed_index = index_type == "int" || index_type == "int32";
        face_list = true;
      } else {
        return false;
      }
    } else if (word != "comment" && word != "obj_info" && !word.empty()) {
      return false;
    }
  }
  return false;  // no end_header
}

/// Reads whole records of `bytes` each from `f` in chunks: next() points at the next record.
class Chunks {
public:
  Chunks(std::FILE* f, const std::string& file) : f_(f), file_(file), buffer_(kChunk) {}

  /// The next `bytes` bytes of the file; throws ConfigError when the file ends first.
  const unsigned char* next(std::size_t bytes) {
    if (end_ - at_ < bytes) {
      std::memmove(buffer_.data(), buffer_.data() + at_, end_ - at_);
      end_ -= at_;
      at_ = 0;
      end_ += std::fread(buffer_.data() + end_, 1, buffer_.size() - end_, f_);
      if (end_ < bytes)
        throw ConfigError(file_ + ": the PLY file ends before its last " + (what_ ? what_ : "record"));
    }
    const unsigned char* p = buffer_.data() + at_;
    at_ += bytes;
    return p;
  }
  void naming(const char* what) { what_ = what; }

private:
  static constexpr std::size_t kChunk = 1 << 22;
  std::FILE* f_;
  const std::string& file_;
  std::vector<unsigned char> buffer_;
  std::size_t at_ = 0, end_ = 0;
  const char* what_ = nullptr;
};

template <typename T>
T load(const unsigned char* p) {
  T x;
  std::memcpy(&x, p, sizeof x);
  return x;
}

float srgbCodeToLinear(unsigned char code) {
  // As loadMesh's assimp path: the code over 255 as a float, then the sRGB curve (IEC 61966-2-1).
  const double x = static_cast<double>(static_cast<float>(code) / 255.0f);
  return static_cast<float>(x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4));
}

}  // namespace

bool readBinaryPly(const MeshEntry& entry, TriangleMesh& out) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(entry.file.c_str(), "rb"), &std::fclose);
  if (!f)
    return false;  // assimp's reading names the error
  Layout layout;
  if (!readHeader(f.get(), layout))
    return false;
  // The counts against the bytes after the header (every vertex record, at least a count per face) and against the
  // int indices of TriangleMesh, before anything is allocated for them.
  const long body = std::ftell(f.get());
  if (body < 0 || std::fseek(f.get(), 0, SEEK_END) != 0)
    throw ConfigError(entry.file + ": cannot seek in the PLY file");
  const long end = std::ftell(f.get());
  if (end < body || std::fseek(f.get(), body, SEEK_SET) != 0)
    throw ConfigError(entry.file + ": cannot seek in the PLY file");
  const std::size_t bytes = static_cast<std::size_t>(end - body);
  const std::size_t max_int = static_cast<std::size_t>(std::numeric_limits<int>::max());
  if (layout.vertices > bytes / layout.vertex_bytes || layout.faces > max_int / 3 ||
      layout.faces > (bytes - layout.vertices * layout.vertex_bytes) / layout.count_bytes || layout.vertices > max_int)
    throw ConfigError(entry.file + ": the PLY header declares " + std::to_string(layout.vertices) + " vertices (" +
                      std::to_string(layout.vertex_bytes) + " bytes each) and " + std::to_string(layout.faces) +
                      " faces: expected no more than the " + std::to_string(bytes) +
                      " bytes after the header hold, and at most " + std::to_string(max_int) + " vertices and " +
                      std::to_string(max_int / 3) + " faces");
  TriangleMesh mesh;
  mesh.name = entry.name;
  mesh.vertices.reserve(layout.vertices + 1);  // room for Embree's 16-byte load of the last vertex
  const bool rgb = layout.rgb[0] >= 0;
  if (rgb)
    mesh.colours.reserve(layout.vertices);
  Chunks chunks(f.get(), entry.file);
  chunks.naming("vertex");
  float table[256];
  for (int c = 0; c < 256; ++c)
    table[c] = srgbCodeToLinear(static_cast<unsigned char>(c));
  for (std::size_t v = 0; v < layout.vertices; ++v) {
    const unsigned char* r = chunks.next(layout.vertex_bytes);
    float p[3];
    for (int k = 0; k < 3; ++k)
      p[k] = layout.xyz_double ? static_cast<float>(load<double>(r + layout.xyz[k])) : load<float>(r + layout.xyz[k]);
    const Eigen::Vector3d local(p[0] * entry.scale.x(), p[1] * entry.scale.y(), p[2] * entry.scale.z());
    mesh.vertices.push_back((entry.pose * local).cast<float>());
    if (rgb)
      mesh.colours.emplace_back(table[r[layout.rgb[0]]], table[r[layout.rgb[1]]], table[r[layout.rgb[2]]]);
  }
  chunks.naming("face");
  // Room for the triangles the rest of the file can hold (a header may declare more: the file then ends early).
  mesh.indices.reserve(3 * std::min(layout.faces, (bytes - layout.vertices * layout.vertex_bytes) /
                                                      (layout.count_bytes + 3 * sizeof(std::uint32_t))));
  const std::size_t nv = layout.vertices;
  for (std::size_t t = 0; t < layout.faces; ++t) {
    const unsigned char* c = chunks.next(layout.count_bytes);
    const std::uint64_t count = layout.count_bytes == 1   ? c[0]
                                : layout.count_bytes == 2 ? load<std::uint16_t>(c)
                                                          : load<std::uint32_t>(c);
    if (count != 3)
      return false;  // a polygon: assimp triangulates it
    const unsigned char* r = chunks.next(3 * sizeof(std::uint32_t));
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = load<std::uint32_t>(r + 4 * k);  // int or uint: a negative int is out of range too
      if (i >= nv) {
        const double named = layout.signed_index ? static_cast<double>(static_cast<std::int32_t>(i)) : i;
        throw ConfigError(entry.file + ": face " + formatNumber(static_cast<double>(t)) + " names vertex " +
                          formatNumber(named) + ", expected [0, " + formatNumber(static_cast<double>(nv)) + ")");
      }
      mesh.indices.push_back(static_cast<int>(i));
    }
  }
  out = std::move(mesh);
  return true;
}

}  // namespace sim
}  // namespace unexmin
