#include <unexmin/sim/mesh.h>

#include <unexmin/sim/ply_reader.h>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace sim {
namespace {

/// Linear light of an sRGB value in [0, 1] (IEC 61966-2-1), clamped to [0, 1] first.
float linearFromSrgb(float c) {
  const double x = std::min(1.0, std::max(0.0, static_cast<double>(c)));
  return static_cast<float>(x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4));
}

}  // namespace

TriangleMesh loadMesh(const MeshEntry& entry) {
  TriangleMesh out;
  if (!readBinaryPly(entry, out))
    out = loadMeshWithAssimp(entry);
  if (out.indices.empty())
    throw ConfigError(entry.file + ": mesh '" + entry.name + "' has no triangle");
  // The spare vertex slot of TriangleMesh::vertices, zeroed (a slot a ray caster reads is never uninitialised).
  out.vertices.reserve(out.vertices.size() + 1);
  out.vertices.emplace_back(0.0f, 0.0f, 0.0f);
  out.vertices.pop_back();
  return out;
}

TriangleMesh loadMeshWithAssimp(const MeshEntry& entry) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(
      entry.file, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices);
  if (!scene || !scene->mRootNode)
    throw ConfigError(entry.file + ": cannot load mesh '" + entry.name + "': " + importer.GetErrorString());
  TriangleMesh out;
  out.name = entry.name;
  bool uvs = scene->mNumMeshes > 0, colours = uvs;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    uvs = uvs && scene->mMeshes[m]->HasTextureCoords(0);
    colours = colours && scene->mMeshes[m]->HasVertexColors(0);
  }
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    const int base = static_cast<int>(out.vertices.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      const Eigen::Vector3d local(p.x * entry.scale.x(), p.y * entry.scale.y(), p.z * entry.scale.z());
      out.vertices.push_back((entry.pose * local).cast<float>());
      if (uvs)
        out.uvs.emplace_back(mesh->mTextureCoords[0][v].x, mesh->mTextureCoords[0][v].y);
      if (colours) {
        const aiColor4D& c = mesh->mColors[0][v];
        out.colours.emplace_back(linearFromSrgb(c.r), linearFromSrgb(c.g), linearFromSrgb(c.b));
      }
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3)
        continue;  // points and lines carry no surface
      for (int k = 0; k < 3; ++k)
        out.indices.push_back(base + static_cast<int>(face.mIndices[k]));
    }
  }
  if (out.indices.empty())
    throw ConfigError(entry.file + ": mesh '" + entry.name + "' has no triangle");
  return out;
}

}  // namespace sim
}  // namespace unexmin
