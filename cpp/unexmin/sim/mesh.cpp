#include <unexmin/sim/mesh.h>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

namespace unexmin {
namespace sim {

TriangleMesh loadMesh(const MeshEntry& entry) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(
      entry.file, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices);
  if (!scene || !scene->mRootNode)
    throw ConfigError(entry.file + ": cannot load mesh '" + entry.name + "': " + importer.GetErrorString());
  TriangleMesh out;
  out.name = entry.name;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    const int base = static_cast<int>(out.vertices.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      const Eigen::Vector3d local(p.x * entry.scale.x(), p.y * entry.scale.y(), p.z * entry.scale.z());
      out.vertices.push_back((entry.pose * local).cast<float>());
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
