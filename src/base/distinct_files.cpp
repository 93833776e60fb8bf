#include "fissure/base/distinct_files.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"

#include <system_error>

namespace fissure {

namespace fs = std::filesystem;

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) {
    const bool same = fs::equivalent(a, b, ec);
    if (!ec) return same;
  }
  const fs::path ca = fs::weakly_canonical(fs::absolute(a, ec), ec);
  const fs::path cb = fs::weakly_canonical(fs::absolute(b, ec), ec);
  return ca.lexically_normal() == cb.lexically_normal();
}

std::vector<RoleAndPath> output_roles(const std::string& role, const std::vector<fs::path>& files) {
  std::vector<RoleAndPath> roles;
  for (const fs::path& f : files) roles.push_back({role, f});
  return roles;
}

void check_distinct_files(const std::vector<RoleAndPath>& inputs, const std::vector<RoleAndPath>& outputs) {
  const auto named = [](const RoleAndPath& f) { return f.role + " " + f.path.string(); };
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const RoleAndPath& out = outputs[i];
    if (out.path.empty()) continue;
    if (out.path == "-") {
      for (std::size_t j = i + 1; j < outputs.size(); ++j)
        if (outputs[j].path == "-") throw InvalidInput(named(out) + " and " + named(outputs[j]) + ": only one result can go to stdout");
      continue;
    }
    if (is_stream_target(out.path)) continue;
    for (const RoleAndPath& in : inputs) {
      if (!in.path.empty() && in.path != "-" && same_file(out.path, in.path))
        throw InvalidInput(named(out) + " is " + named(in) + ": writing it would destroy what the command reads; give the output another name");
    }
    for (std::size_t j = i + 1; j < outputs.size(); ++j) {
      const RoleAndPath& other = outputs[j];
      if (!other.path.empty() && other.path != "-" && same_file(out.path, other.path))
        throw InvalidInput(named(out) + " and " + named(other) + " name the same file: one would overwrite the other; give each its own");
    }
  }
}

}  // namespace fissure
