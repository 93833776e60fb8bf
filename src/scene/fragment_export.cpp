#include "fissure/scene/fragment_export.hpp"

#include "fissure/mesh/appearance_transfer.hpp"

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <map>
#include <memory>
#include <tuple>

namespace fissure {
namespace {

// A UV chart: the crack a triangle lies on (≥ 0), or −1 − axis for an outer triangle
// box-projected along that axis.
int chart_of(const FragmentMesh& f, Eigen::Index t) {
  const int crack = f.triangle_crack[static_cast<std::size_t>(t)];
  if (crack >= 0) return crack;
  const Eigen::Vector3d a = f.vertices.row(f.triangles(t, 0)), b = f.vertices.row(f.triangles(t, 1)),
                        c = f.vertices.row(f.triangles(t, 2));
  Eigen::Index axis = 0;
  (b - a).cross(c - a).cwiseAbs().maxCoeff(&axis);
  return -1 - static_cast<int>(axis);
}

// Two unit directions spanning the chart's plane, right-handed about its normal.
Eigen::Matrix<double, 2, 3> chart_basis(int chart, const std::vector<CrackSurface>& cracks) {
  Eigen::Vector3d n;
  if (chart >= 0) {
    n = cracks[static_cast<std::size_t>(chart)].normal.normalized();
  } else {
    n = Eigen::Vector3d::Unit(-1 - chart);
  }
  // The axis least along n, made perpendicular: a well-conditioned first direction.
  Eigen::Index least = 0;
  n.cwiseAbs().minCoeff(&least);
  const Eigen::Vector3d u = (Eigen::Vector3d::Unit(least) - n * n(least)).normalized();
  Eigen::Matrix<double, 2, 3> basis;
  basis.row(0) = u.transpose();
  basis.row(1) = n.cross(u).transpose();
  return basis;
}

// The scene's materials: the input's (or `surface`), then the crack's, named apart from them.
std::vector<ExportMaterial> scene_materials(const SurfaceAppearance& appearance) {
  std::vector<ExportMaterial> materials;
  for (const auto& m : appearance.materials) materials.push_back({m.name, m.colour, {}});
  if (materials.empty()) materials.push_back({"surface", Eigen::Vector3d(0.62, 0.60, 0.56), {}});
  std::string crack = "crack";
  for (int k = 1; std::any_of(materials.begin(), materials.end(), [&](const ExportMaterial& m) { return m.name == crack; }); ++k) {
    const std::string digits = std::to_string(k);
    crack = "crack." + std::string(digits.size() < 3 ? 3 - digits.size() : 0, '0') + digits;
  }
  materials.push_back({crack, Eigen::Vector3d(0.30, 0.28, 0.26), {}});
  return materials;
}

}  // namespace

std::string fragment_name(int index, int count) {
  std::string digits = std::to_string(index);
  const std::size_t width = std::max<std::size_t>(3, std::to_string(std::max(0, count - 1)).size());
  if (digits.size() < width) digits.insert(0, width - digits.size(), '0');
  return "fragment_" + digits;
}

ExportScene fragment_scene(const std::vector<FragmentMesh>& fragments, const std::vector<CrackSurface>& cracks,
                           double density, const SurfaceAppearance& appearance) {
  ExportScene scene;
  scene.materials = scene_materials(appearance);
  const int crack_material = static_cast<int>(scene.materials.size()) - 1;
  const std::unique_ptr<const AppearanceTransfer> transfer =
      appearance.empty() ? nullptr : std::make_unique<const AppearanceTransfer>(appearance);
  const int count = static_cast<int>(fragments.size());
  scene.parts.reserve(fragments.size());
  for (int k = 0; k < count; ++k) {
    const FragmentMesh& f = fragments[static_cast<std::size_t>(k)];
    ExportPart part;
    part.name = fragment_name(k, count);
    part.translation = f.centre;
    // (vertex, chart, material, uv) → exported vertex. A projected chart's UVs are a function
    // of the position; transferred UVs (chart −100) are shared where they agree.
    std::map<std::tuple<int, int, int, double, double>, int> split;
    std::map<int, Eigen::Matrix<double, 2, 3>> bases;
    std::vector<Eigen::Vector3d> positions;
    std::vector<Eigen::Vector2d> uvs;
    part.triangles.resize(f.triangles.rows(), 3);
    part.triangle_material.resize(static_cast<std::size_t>(f.triangles.rows()));
    for (Eigen::Index t = 0; t < f.triangles.rows(); ++t) {
      const bool outer = f.triangle_crack[static_cast<std::size_t>(t)] < 0;
      int material = outer ? 0 : crack_material, source = -1;
      if (outer && transfer) {
        const Eigen::Vector3d centroid =
            (f.vertices.row(f.triangles(t, 0)) + f.vertices.row(f.triangles(t, 1)) + f.vertices.row(f.triangles(t, 2))).transpose() / 3.0;
        source = transfer->nearest_triangle(centroid);
        material = transfer->material_of(source);
      }
      const bool transferred = source >= 0 && appearance.has_uvs();
      const int chart = transferred ? -100 : chart_of(f, t);
      auto basis = bases.end();
      if (!transferred) {
        basis = bases.find(chart);
        if (basis == bases.end()) basis = bases.emplace(chart, chart_basis(chart, cracks)).first;
      }
      for (int i = 0; i < 3; ++i) {
        const int v = f.triangles(t, i);
        const Eigen::Vector3d x = f.vertices.row(v).transpose();
        const Eigen::Vector2d uv = transferred ? transfer->uv_at(source, x) : Eigen::Vector2d(basis->second * x);
        const auto [it, inserted] = split.try_emplace({v, chart, material, uv.x(), uv.y()}, static_cast<int>(positions.size()));
        if (inserted) {
          positions.push_back(x - f.centre);
          uvs.push_back(uv);
        }
        part.triangles(t, i) = it->second;
      }
      part.triangle_material[static_cast<std::size_t>(t)] = material;
    }
    part.vertices.resize(static_cast<Eigen::Index>(positions.size()), 3);
    part.uvs.resize(static_cast<Eigen::Index>(uvs.size()), 2);
    for (std::size_t i = 0; i < positions.size(); ++i) {
      part.vertices.row(static_cast<Eigen::Index>(i)) = positions[i].transpose();
      part.uvs.row(static_cast<Eigen::Index>(i)) = uvs[i].transpose();
    }
    nlohmann::ordered_json contacts = nlohmann::ordered_json::array();
    for (const FragmentContact& c : f.contacts)
      contacts.push_back({{"fragment", fragment_name(c.fragment, count)}, {"area_m2", c.area}});
    const nlohmann::ordered_json extras = {{"fragment", k},
                                           {"volume_m3", f.volume},
                                           {"mass_kg", f.volume * density},
                                           {"centre_of_mass_m", {f.centre.x(), f.centre.y(), f.centre.z()}},
                                           {"crack_onset_time", f.crack_onset_time},
                                           {"contacts", contacts}};
    part.extras_json = extras.dump();
    scene.parts.push_back(std::move(part));
  }
  return scene;
}

}  // namespace fissure
