#include <unexmin/sim/collision_shape.h>

#include <btBulletDynamicsCommon.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace unexmin {
namespace sim {
namespace {

/// What a cache file starts with: the file is the BVH of this mesh, built by this Bullet, when every field matches.
struct CacheHeader {
  char magic[8] = {'U', 'X', 'B', 'V', 'H', '0', '1', '\0'};
  std::uint32_t bullet_version = 0;
  std::uint32_t scalar_bytes = 0;
  std::uint64_t vertices = 0, triangles = 0;
  std::uint64_t mesh_hash = 0;
  std::uint64_t payload_bytes = 0;  ///< Bullet's serialised BVH after the header
  std::uint64_t payload_hash = 0;
};

/// A 64-bit hash of `bytes` bytes at `data`, continuing from `h` (eight bytes at a time, multiply and xor-shift).
std::uint64_t hashBytes(const void* data, std::size_t bytes, std::uint64_t h) {
  const auto* p = static_cast<const unsigned char*>(data);
  std::size_t i = 0;
  auto mix = [&h](std::uint64_t w) {
    h = (h ^ w) * 0x9E3779B97F4A7C15ULL;
    h ^= h >> 29;
  };
  for (; i + 8 <= bytes; i += 8) {
    std::uint64_t w;
    std::memcpy(&w, p + i, 8);
    mix(w);
  }
  std::uint64_t tail = 0;
  std::memcpy(&tail, p + i, bytes - i);
  mix(tail ^ (static_cast<std::uint64_t>(bytes) << 56));
  return h;
}

std::uint64_t meshHash(const TriangleMesh& mesh) {
  std::uint64_t h =
      hashBytes(mesh.vertices.data(), mesh.vertices.size() * sizeof(Eigen::Vector3f), 0x243F6A8885A308D3ULL);
  return hashBytes(mesh.indices.data(), mesh.indices.size() * sizeof(int), h);
}

CacheHeader headerOf(const TriangleMesh& mesh, std::uint64_t mesh_hash) {
  CacheHeader h;
  h.bullet_version = static_cast<std::uint32_t>(btGetVersion());
  h.scalar_bytes = sizeof(btScalar);
  h.vertices = mesh.vertices.size();
  h.triangles = mesh.triangleCount();
  h.mesh_hash = mesh_hash;
  return h;
}

using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

}  // namespace

std::string bvhCacheFile(const MeshEntry& entry, const TriangleMesh& mesh) {
  return mesh.triangleCount() >= kBvhCacheMinTriangles ? entry.file + ".bvh" : std::string();
}

MeshCollisionShape::MeshCollisionShape(const TriangleMesh& mesh, const std::string& cache_file) {
  static_assert(sizeof(btScalar) == sizeof(float), "Bullet must be built with float scalars");
  // Parts of kBulletPartTriangles triangles over the same vertices (one part, as Bullet's own constructor makes it,
  // below that): a triangle past 2^21 - 1 in one part would be read back by the BVH as a part that does not exist.
  array_ = std::make_unique<btTriangleIndexVertexArray>();
  const std::size_t triangles = mesh.triangleCount();
  for (std::size_t first = 0; first == 0 || first < triangles; first += kBulletPartTriangles) {
    btIndexedMesh part;
    part.m_numTriangles = static_cast<int>(std::min(kBulletPartTriangles, triangles - first));
    part.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(mesh.indices.data() + 3 * first);
    part.m_triangleIndexStride = 3 * static_cast<int>(sizeof(int));
    part.m_numVertices = static_cast<int>(mesh.vertices.size());
    part.m_vertexBase = reinterpret_cast<const unsigned char*>(mesh.vertices.data());
    part.m_vertexStride = static_cast<int>(sizeof(Eigen::Vector3f));
    array_->addIndexedMesh(part, PHY_INTEGER);
  }
  // As btBvhTriangleMeshShape(array, true) builds it, with the BVH held here: read from or written to the cache.
  shape_ = std::make_unique<btBvhTriangleMeshShape>(array_.get(), true, false);
  const std::uint64_t hash = cache_file.empty() ? 0 : meshHash(mesh);
  from_cache_ = !cache_file.empty() && readCache(cache_file, mesh, hash);
  if (!from_cache_) {
    built_ = std::make_unique<btOptimizedBvh>();
    built_->build(array_.get(), true, shape_->getLocalAabbMin(), shape_->getLocalAabbMax());
    if (!cache_file.empty())
      writeCache(cache_file, mesh, hash);
  }
  shape_->setOptimizedBvh(in_place_ ? in_place_ : built_.get());
}

MeshCollisionShape::~MeshCollisionShape() {
  shape_.reset();  // it does not own the BVH
  if (in_place_)
    in_place_->~btOptimizedBvh();  // its arrays live in buffer_
  btAlignedFree(buffer_);
}

bool MeshCollisionShape::readCache(const std::string& cache_file, const TriangleMesh& mesh, std::uint64_t mesh_hash) {
  const CacheHeader expected = headerOf(mesh, mesh_hash);
  File f(std::fopen(cache_file.c_str(), "rb"), &std::fclose);
  CacheHeader h;
  if (!f || std::fread(&h, sizeof h, 1, f.get()) != 1 || std::memcmp(h.magic, expected.magic, sizeof h.magic) != 0 ||
      h.bullet_version != expected.bullet_version || h.scalar_bytes != expected.scalar_bytes ||
      h.vertices != expected.vertices || h.triangles != expected.triangles || h.mesh_hash != expected.mesh_hash ||
      h.payload_bytes == 0 || h.payload_bytes > 0xFFFFFFF0ULL)
    return false;
  void* buffer = btAlignedAlloc(static_cast<std::size_t>(h.payload_bytes), 16);
  if (!buffer)
    return false;
  btOptimizedBvh* bvh = nullptr;
  char extra;
  if (std::fread(buffer, 1, h.payload_bytes, f.get()) == h.payload_bytes && std::fread(&extra, 1, 1, f.get()) == 0 &&
      hashBytes(buffer, h.payload_bytes, 0) == h.payload_hash)
    bvh = btOptimizedBvh::deSerializeInPlace(buffer, static_cast<unsigned>(h.payload_bytes), false);
  if (!bvh) {
    btAlignedFree(buffer);
    return false;
  }
  buffer_ = buffer;
  in_place_ = bvh;
  return true;
}

void MeshCollisionShape::writeCache(const std::string& cache_file, const TriangleMesh& mesh, std::uint64_t mesh_hash) {
  const unsigned bytes = built_->calculateSerializeBufferSize();
  void* buffer = btAlignedAlloc(bytes, 16);
  if (!buffer || !built_->serializeInPlace(buffer, bytes, false)) {
    btAlignedFree(buffer);
    return;
  }
  CacheHeader h = headerOf(mesh, mesh_hash);
  h.payload_bytes = bytes;
  h.payload_hash = hashBytes(buffer, bytes, 0);
  const std::string temporary = cache_file + ".tmp" + std::to_string(::getpid());
  bool written = false;
  {
    File f(std::fopen(temporary.c_str(), "wb"), &std::fclose);
    written = f && std::fwrite(&h, sizeof h, 1, f.get()) == 1 && std::fwrite(buffer, 1, bytes, f.get()) == bytes &&
              std::fflush(f.get()) == 0;
  }
  if (!written || std::rename(temporary.c_str(), cache_file.c_str()) != 0)
    std::remove(temporary.c_str());
  // Serialising left the buffer with a copy of the BVH that only needs its pointers set: use it, free the built one.
  btOptimizedBvh* bvh = btOptimizedBvh::deSerializeInPlace(buffer, bytes, false);
  if (!bvh) {
    btAlignedFree(buffer);
    return;
  }
  buffer_ = buffer;
  in_place_ = bvh;
  built_.reset();
}

}  // namespace sim
}  // namespace unexmin
