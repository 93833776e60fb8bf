#include "fissure/scene/scene_merge.hpp"

#include "fissure/base/error.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>

namespace fissure {
namespace {

struct SliceId {
  int k = 0, n = 0;
  std::string run;
};

SliceId slice_id(const ExportScene& s, const std::string& name) {
  const auto extras = nlohmann::json::parse(s.extras_json, nullptr, false);
  const auto refuse = [&] {
    return InvalidInput(name + ": not a slice of fissure scene fracture (its scene extras name no run and slice)");
  };
  if (!extras.is_object() || !extras.contains("fissure") || !extras["fissure"].is_object()) throw refuse();
  const auto& f = extras["fissure"];
  if (!f.contains("slice") || !f["slice"].is_array() || f["slice"].size() != 2 || !f["slice"][0].is_number_integer() ||
      !f["slice"][1].is_number_integer() || !f.contains("run") || !f["run"].is_string())
    throw refuse();
  SliceId id{f["slice"][0].get<int>(), f["slice"][1].get<int>(), f["run"].get<std::string>()};
  if (id.n < 1 || id.k < 1 || id.k > id.n) throw refuse();
  return id;
}

// A fractured body's node has "fissure" extras that say how many fragment parts follow it; -1
// for any other node.
int fragment_count(const ExportPart& p, const std::string& name) {
  const auto extras = nlohmann::json::parse(p.extras_json, nullptr, false);
  if (!extras.is_object() || !extras.contains("fissure") || !extras["fissure"].is_object()) return -1;
  const auto& f = extras["fissure"];
  if (!f.contains("fragments") || !f["fragments"].is_number_unsigned() || f["fragments"].get<std::uint64_t>() > 100000000)
    throw InvalidInput(name + ": node " + p.name + " has fissure extras without a fragment count");
  return f["fragments"].get<int>();
}

// The slice's nodes without fragments (the scene's own nodes), as part indices.
std::vector<std::size_t> skeleton(const ExportScene& s, const std::string& name) {
  std::vector<std::size_t> nodes;
  for (std::size_t p = 0; p < s.parts.size();) {
    nodes.push_back(p);
    const std::size_t fragments = static_cast<std::size_t>(std::max(0, fragment_count(s.parts[p], name)));
    for (std::size_t f = p + 1; f <= p + fragments; ++f) {
      if (f >= s.parts.size() || s.parts[f].parent != static_cast<int>(p))
        throw InvalidInput(name + ": node " + std::to_string(p) + " (" + s.parts[p].name + ") should be followed by its " +
                           std::to_string(fragments) + " fragments");
    }
    p += 1 + fragments;
  }
  return nodes;
}

}  // namespace

std::string scene_slice_extras(const std::string& run, int k, int n) {
  const nlohmann::ordered_json extras = {{"fissure", {{"slice", {k, n}}, {"run", run}}}};
  return extras.dump();
}

ExportScene merge_scene_slices(const std::vector<ExportScene>& slices, const std::vector<std::string>& names) {
  if (slices.empty()) throw InvalidInput("scene merge: no slices given");
  std::vector<SliceId> ids;
  for (std::size_t i = 0; i < slices.size(); ++i) ids.push_back(slice_id(slices[i], names[i]));
  const int n = ids[0].n;
  std::vector<int> slice_of_k(static_cast<std::size_t>(n) + 1, -1);
  const auto which = [&](std::size_t j) {
    return ids[j].n == 1 ? std::string("an unsliced run's output") : "slice " + std::to_string(ids[j].k) + "/" + std::to_string(ids[j].n);
  };
  for (std::size_t i = 0; i < slices.size(); ++i) {
    if (ids[i].run != ids[0].run)
      throw InvalidInput(names[i] + ": a slice of another run than " + names[0] +
                         " (another scene, assignments, seed, age, up or tet count)");
    if (ids[i].n != n)
      throw InvalidInput(names[i] + " is " + which(i) + " and " + names[0] + " is " + which(0) +
                         ": merge the slices of one --bodies K/N split");
    if (slice_of_k[static_cast<std::size_t>(ids[i].k)] >= 0)
      throw InvalidInput(names[i] + ": slice " + std::to_string(ids[i].k) + "/" + std::to_string(n) + " is also " +
                         names[static_cast<std::size_t>(slice_of_k[static_cast<std::size_t>(ids[i].k)])]);
    slice_of_k[static_cast<std::size_t>(ids[i].k)] = static_cast<int>(i);
  }
  for (int k = 1; k <= n; ++k)
    if (slice_of_k[static_cast<std::size_t>(k)] < 0)
      throw InvalidInput("scene merge: slice " + std::to_string(k) + "/" + std::to_string(n) + " is missing");

  std::vector<std::vector<std::size_t>> skeletons;
  const std::size_t first = static_cast<std::size_t>(slice_of_k[1]);
  for (std::size_t i = 0; i < slices.size(); ++i) {
    skeletons.push_back(skeleton(slices[i], names[i]));
    bool same = skeletons[i].size() == skeletons[0].size() && slices[i].materials.size() == slices[0].materials.size();
    for (std::size_t s = 0; same && s < skeletons[i].size(); ++s)
      same = slices[i].parts[skeletons[i][s]].name == slices[0].parts[skeletons[0][s]].name;
    for (std::size_t m = 0; same && m < slices[i].materials.size(); ++m) same = slices[i].materials[m].name == slices[0].materials[m].name;
    if (!same) throw InvalidInput(names[i] + ": its nodes or materials differ from " + names[0] + "'s");
  }

  ExportScene out;
  out.materials = slices[first].materials;
  out.extras_json = scene_slice_extras(ids[0].run, 1, 1);
  std::vector<int> out_of_skeleton(skeletons[0].size(), -1);
  for (std::size_t s = 0; s < skeletons[0].size(); ++s) {
    int from = -1;
    for (std::size_t i = 0; i < slices.size(); ++i) {
      if (fragment_count(slices[i].parts[skeletons[i][s]], names[i]) < 0) continue;
      if (from >= 0)
        throw InvalidInput(names[i] + ": " + slices[i].parts[skeletons[i][s]].name + " is fractured in " +
                           names[static_cast<std::size_t>(from)] + " too");
      from = static_cast<int>(i);
    }
    const std::size_t i = from >= 0 ? static_cast<std::size_t>(from) : first;
    const std::vector<ExportPart>& parts = slices[i].parts;
    const std::size_t p = skeletons[i][s];
    // The node's parent, a node of the scene: by its place in the skeleton.
    ExportPart node = parts[p];
    if (node.parent >= 0) {
      const auto it = std::find(skeletons[i].begin(), skeletons[i].end(), static_cast<std::size_t>(node.parent));
      if (it == skeletons[i].end()) throw InvalidInput(names[i] + ": node " + std::to_string(p) + "'s parent is a fragment");
      node.parent = out_of_skeleton[static_cast<std::size_t>(it - skeletons[i].begin())];
    }
    out_of_skeleton[s] = static_cast<int>(out.parts.size());
    out.parts.push_back(std::move(node));
    const int fragments = std::max(0, fragment_count(parts[p], names[i]));
    for (int f = 1; f <= fragments; ++f) {
      ExportPart fragment = parts[p + static_cast<std::size_t>(f)];
      fragment.parent = out_of_skeleton[s];
      out.parts.push_back(std::move(fragment));
    }
  }
  return out;
}

}  // namespace fissure
