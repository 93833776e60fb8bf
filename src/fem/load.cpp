#include "fissure/fem/load.hpp"

#include "fissure/base/error.hpp"

#include <charconv>
#include <cmath>

namespace fissure {

LoadSpec parse_load(std::string_view spec) {
  LoadSpec load;
  load.spec = std::string(spec);
  const std::size_t eq = spec.rfind('=');
  if (eq == std::string_view::npos || eq == 0) {
    throw InvalidInput("load '" + load.spec + "': expected SELECTION=fx,fy,fz (newtons)");
  }
  load.selection = parse_selection(spec.substr(0, eq));
  std::string_view numbers = spec.substr(eq + 1);
  int count = 0;
  std::size_t pos = 0;
  while (pos <= numbers.size()) {
    const std::size_t comma = std::min(numbers.find(',', pos), numbers.size());
    const std::string item(numbers.substr(pos, comma - pos));
    double value = 0.0;
    const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), value);
    if (item.empty() || ec != std::errc() || end != item.data() + item.size() || !std::isfinite(value)) {
      throw InvalidInput("load '" + load.spec + "': force component '" + item + "' is not a finite number");
    }
    if (count < 3) load.force[count] = value;
    ++count;
    pos = comma + 1;
  }
  if (count != 3) {
    throw InvalidInput("load '" + load.spec + "': expected 3 force components fx,fy,fz, got " +
                       std::to_string(count));
  }
  return load;
}

Eigen::VectorXd assemble_load(const TetMesh& mesh, const LoadSpec& load) {
  const SelectedRegion region = resolve_selection(mesh, load.selection);
  const Eigen::VectorXd areas = face_areas(mesh, region);
  const double total_area = areas.sum();
  if (region.faces.empty() || !(total_area > 0.0)) {
    throw InvalidInput("load patch '" + load.selection.spec + "' touches no boundary face of " +
                       (mesh.source_name().empty() ? std::string("the mesh") : mesh.source_name()));
  }
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(mesh.node_count()));
  for (std::size_t k = 0; k < region.faces.size(); ++k) {
    const Eigen::Vector3d per_node = load.force * (areas[static_cast<Eigen::Index>(k)] / total_area / 3.0);
    for (int v : region.faces[k]) f.segment<3>(3 * static_cast<Eigen::Index>(v)) += per_node;
  }
  return f;
}

Eigen::VectorXd gravity_load(const TetMesh& mesh, double density, const Eigen::Vector3d& g) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(mesh.node_count()));
  for (int t = 0; t < mesh.tet_count(); ++t) {
    const Eigen::Vector3d share = g * (density * mesh.volumes()[t] / 4.0);
    for (int a = 0; a < 4; ++a) f.segment<3>(3 * static_cast<Eigen::Index>(mesh.tets()(t, a))) += share;
  }
  return f;
}

}  // namespace fissure
