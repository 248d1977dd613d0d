#include <unexmin/sensors/vision/surface_materials.h>

#include <algorithm>

namespace unexmin {
namespace sensors {
namespace vision {

const Eigen::Vector3d SurfaceMaterials::kHullAlbedo{0.95, 0.75, 0.10};

SurfaceMaterials::SurfaceMaterials(const sim::WorldConfig& config) : SurfaceMaterials(config, nullptr) {}

SurfaceMaterials::SurfaceMaterials(const sim::World& world) : SurfaceMaterials(world.config(), &world) {}

SurfaceMaterials::SurfaceMaterials(const sim::WorldConfig& config, const sim::World* world)
    : config_(&config), world_(world) {
  meshes_.resize(config.meshes.size());
  for (std::size_t i = 0; i < config.meshes.size(); ++i) {
    const sim::MeshEntry& e = config.meshes[i];
    Mesh& m = meshes_[i];
    m.albedo << static_cast<float>(e.albedo.x()), static_cast<float>(e.albedo.y()), static_cast<float>(e.albedo.z()),
        0.0f;
    if (e.material.checkerboard()) {
      m.board = std::make_unique<sim::Material>(e.material);
      m.board->albedo = e.albedo;
    } else if (e.material.textured()) {
      sim::Material material = e.material;
      material.albedo = e.albedo;  // the mesh's albedo is its material's mean
      m.texture = std::make_unique<RockTexture>(material, "meshes[" + formatNumber(i) + "].material.");
      if (config.geology && e.material.kind == "rock") {
        const geo::Geology& g = *config.geology;
        for (std::size_t id = 0; id <= g.bodies().size(); ++id) {
          const Eigen::Vector3d rock = g.rock(static_cast<int>(id)).albedo;
          Eigen::Array3f t;
          for (int k = 0; k < 3; ++k)
            t[k] = static_cast<float>(rock[k] / std::max(1e-3, e.albedo[k]));
          m.tint.push_back(t);
        }
      }
    }
    m.to_mesh = e.pose.linear().transpose().cast<float>();
    m.origin = e.pose.translation().cast<float>();
    if (e.material.mapped()) {
      if (!world)
        throw ConfigError(config.file + ": 'meshes[" + formatNumber(i) + "].material.kind' = '" + e.material.kind +
                          "' needs the world's loaded meshes");
      m.data = &world->mesh(i);
      m.image = world->image(i);
    }
  }
}

const SurfaceMaterials& SurfaceMaterials::of(const sim::WorldConfig& config, std::unique_ptr<SurfaceMaterials>& cache) {
  if (!cache || cache->config_ != &config || cache->world_ || cache->size() != config.meshes.size())
    cache = std::make_unique<SurfaceMaterials>(config);
  return *cache;
}

const SurfaceMaterials& SurfaceMaterials::of(const sim::World& world, std::unique_ptr<SurfaceMaterials>& cache) {
  if (!cache || cache->world_ != &world || cache->size() != world.config().meshes.size())
    cache = std::make_unique<SurfaceMaterials>(world);
  return *cache;
}

Eigen::Array3f SurfaceMaterials::tintAt(const Mesh& m, const Eigen::Vector3f& p) const {
  if (m.tint.empty())
    return Eigen::Array3f::Ones();
  return m.tint[static_cast<std::size_t>(config_->geology->bodyAt(p.cast<double>()))];
}

Eigen::Array3f SurfaceMaterials::albedo(const raycast::Hit& hit, const Eigen::Vector3f& p) const {
  const auto mesh = static_cast<std::size_t>(hit.index);
  if (!mapped(mesh))
    return albedo(mesh, p);
  float out[3];
  mappedAlbedo(hit, out);
  return Eigen::Array3f(out[0], out[1], out[2]);
}

const float* SurfaceMaterials::mappedAlbedo(const raycast::Hit& hit, float* out) const {
  const Mesh& m = meshes_[static_cast<std::size_t>(hit.index)];
  const sim::TriangleMesh& mesh = *m.data;
  Eigen::Array3f a = m.albedo.head<3>();
  if (hit.primitive >= 0 && static_cast<std::size_t>(hit.primitive) < mesh.triangleCount()) {
    const int* tri = &mesh.indices[3 * static_cast<std::size_t>(hit.primitive)];
    const float w0 = 1.0f - hit.u - hit.v;
    if (m.image) {
      const Eigen::Vector2f uv = w0 * mesh.uvs[tri[0]] + hit.u * mesh.uvs[tri[1]] + hit.v * mesh.uvs[tri[2]];
      a *= m.image->sample(uv.x(), uv.y());
    } else {
      a *= (w0 * mesh.colours[tri[0]] + hit.u * mesh.colours[tri[1]] + hit.v * mesh.colours[tri[2]]).array();
    }
  }
  out[0] = a[0];
  out[1] = a[1];
  out[2] = a[2];
  return out;
}

Eigen::Array3f SurfaceMaterials::albedo(std::size_t mesh, const Eigen::Vector3f& p) const {
  const Mesh& m = meshes_.at(mesh);
  if (m.board)
    return sim::checkerboardAlbedo(*m.board, m.to_mesh * (p - m.origin)).array();
  if (!m.texture)
    return m.albedo.head<3>();
  return (m.texture->albedo(m.to_mesh * (p - m.origin)) * tintAt(m, p)).min(1.0f);
}

void SurfaceMaterials::shade(std::size_t mesh, const Eigen::Vector3f& p, const Eigen::Vector3f& n, float* albedo,
                             Eigen::Vector3f& shading) const {
  const Mesh& m = meshes_[mesh];
  if (m.board) {
    Eigen::Map<Eigen::Vector3f> out(albedo);
    out = sim::checkerboardAlbedo(*m.board, m.to_mesh * (p - m.origin));
    shading = n;
    return;
  }
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
  const Eigen::Array3f tint = tintAt(m, p);
  for (int k = 0; k < 3; ++k)
    albedo[k] = std::min(1.0f, albedo[k] * tint[k]);  // a pale rock's texture peaks stay physical
}

void SurfaceMaterials::shadeMany(std::size_t mesh, const Eigen::Matrix3f& rotation, const Eigen::Vector3f& translation,
                                 int n, const float* px, const float* py, const float* pz, float* nx, float* ny,
                                 float* nz, float* const albedo[3], bool simd) const {
  const Mesh& m = meshes_.at(mesh);
  if (m.board) {  // the normals stay the faces'
    const Eigen::Matrix3f r = m.to_mesh * rotation;
    const Eigen::Vector3f t = m.to_mesh * (translation - m.origin);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3f a = sim::checkerboardAlbedo(*m.board, r * Eigen::Vector3f(px[i], py[i], pz[i]) + t);
      for (int k = 0; k < 3; ++k)
        albedo[k][i] = a[k];
    }
    return;
  }
  // frame A -> world -> mesh frame, as one rotation and translation
  m.texture->shadeManyFrom(m.to_mesh * rotation, m.to_mesh * (translation - m.origin), n, px, py, pz, nx, ny, nz,
                           albedo, simd);
  if (m.tint.empty())
    return;
  for (int i = 0; i < n; ++i) {  // the rock behind the wall at each point (frame A -> world)
    const Eigen::Array3f tint = tintAt(m, rotation * Eigen::Vector3f(px[i], py[i], pz[i]) + translation);
    for (int k = 0; k < 3; ++k)
      albedo[k][i] = std::min(1.0f, albedo[k][i] * tint[k]);
  }
}

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin
