#pragma once
/// A command that reads some files and writes others must not write one over another: `-o` given
/// the input scene's name, or `-o x --report x`, would each lose a file while the run reports
/// success. Commands call check_distinct_files() with their inputs and outputs before any work.

#include <filesystem>
#include <string>
#include <vector>

namespace fissure {

/// A file a command reads or writes, and how the user named it ("-o", "--report", "the scene").
struct RoleAndPath {
  std::string role;
  std::filesystem::path path;
};

/// True when `a` and `b` are the same file: the same inode when both exist (hard links and
/// symbolic links included), else the same path once made absolute, normalised and its links
/// followed as far as they exist.
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

/// The files one option writes (an OBJ and its .mtl), each under that option's role.
std::vector<RoleAndPath> output_roles(const std::string& role, const std::vector<std::filesystem::path>& files);

/// Throws InvalidInput naming both roles and the file when an output is the same file as an input
/// or as another output. Empty paths are ignored; so are streams ("-", /dev/null, a FIFO, a
/// terminal), which are written, not replaced, except that only one output may be "-".
void check_distinct_files(const std::vector<RoleAndPath>& inputs, const std::vector<RoleAndPath>& outputs);

}  // namespace fissure
