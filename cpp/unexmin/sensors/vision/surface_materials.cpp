#include <unexmin/sensors/vision/surface_materials.h>

namespace unexmin {
namespace sensors {
namespace vision {

SurfaceMaterials::SurfaceMaterials(const sim::WorldConfig& config) : config_(&config) {
  meshes_.resize(config.meshes.size());
  for (std::size_t i = 0; i < config.meshes.size(); ++i) {
    const sim::MeshEntry& e = config.meshes[i];
    Mesh& m = meshes_[i];
    m.albedo << static_cast<float>(e.albedo.x()), static_cast<float>(e.albedo.y()), static_cast<float>(e.albedo.z()),
        0.0f;
    if (e.material.textured()) {
      sim::Material material = e.material;
      material.albedo = e.albedo;  // the mesh's albedo is its material's mean
      m.texture = std::make_unique<RockTexture>(material, "meshes[" + formatNumber(i) + "].material.");
    }
    m.to_mesh = e.pose.linear().transpose().cast<float>();
    m.origin = e.pose.translation().cast<float>();
  }
}

const SurfaceMaterials& SurfaceMaterials::of(const sim::WorldConfig& config, std::unique_ptr<SurfaceMaterials>& cache) {
  if (!cache || cache->config_ != &config || cache->size() != config.meshes.size())
    cache = std::make_unique<SurfaceMaterials>(config);
  return *cache;
}

Eigen::Array3f SurfaceMaterials::albedo(std::size_t mesh, const Eigen::Vector3f& p) const {
  const Mesh& m = meshes_.at(mesh);
  if (!m.texture)
    return m.albedo.head<3>();
  return m.texture->albedo(m.to_mesh * (p - m.origin));
}

void SurfaceMaterials::shade(std::size_t mesh, const Eigen::Vector3f& p, const Eigen::Vector3f& n, float* albedo,
                             Eigen::Vector3f& shading) const {
  const Mesh& m = meshes_[mesh];
  if (!m.texture) {
    albedo[0] = m.albedo[0];
    albedo[1] = m.albedo[1];
    albedo[2] = m.albedo[2];
    shading = n;
    return;
  }
  Eigen::Vector3f local;
  m.texture->shade(m.to_mesh * (p - m.origin), m.to_mesh * n, albedo, local);
  shading = m.to_mesh.transpose() * local;
}

void SurfaceMaterials::shadeMany(std::size_t mesh, const Eigen::Matrix3f& rotation, const Eigen::Vector3f& translation,
                                 int n, const float* px, const float* py, const float* pz, float* nx, float* ny,
                                 float* nz, float* const albedo[3], bool simd) const {
  const Mesh& m = meshes_.at(mesh);
  // frame A -> world -> mesh frame, as one rotation and translation
  m.texture->shadeManyFrom(m.to_mesh * rotation, m.to_mesh * (translation - m.origin), n, px, py, pz, nx, ny, nz,
                           albedo, simd);
}

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin
