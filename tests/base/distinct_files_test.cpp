// check_distinct_files(): an output named like an input or like another output is refused
// before any work, through every way two names can reach one file.

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/distinct_files.hpp"
#include "fissure/base/error.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

namespace fissure {
namespace {
namespace fs = std::filesystem;

// The message of the InvalidInput check_distinct_files throws, or "" when it accepts.
std::string refusal(const std::vector<RoleAndPath>& inputs, const std::vector<RoleAndPath>& outputs) {
  try {
    check_distinct_files(inputs, outputs);
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return {};
}

TEST(DistinctFiles, OneFileByAnyNameIsOneFile) {
  const fs::path dir = test::fresh_temp_dir("distinct");
  write_file_atomically(dir / "scene.glb", "scene");
  fs::create_directories(dir / "sub");
  fs::create_symlink(dir / "scene.glb", dir / "link.glb");
  fs::create_hard_link(dir / "scene.glb", dir / "hard.glb");
  for (const fs::path& name : {dir / "scene.glb", dir / "sub" / ".." / "scene.glb", dir / "." / "scene.glb",
                               dir / "link.glb", dir / "hard.glb"}) {
    EXPECT_TRUE(same_file(dir / "scene.glb", name)) << name;
    const std::string m = refusal({{"the input scene", dir / "scene.glb"}}, {{"-o", name}});
    EXPECT_NE(m.find("-o " + name.string() + " is the input scene " + (dir / "scene.glb").string()), std::string::npos) << m;
  }
  // A relative name is the same file as its absolute one.
  const fs::path cwd = fs::current_path();
  fs::current_path(dir);
  EXPECT_TRUE(same_file("scene.glb", dir / "scene.glb"));
  EXPECT_TRUE(same_file("new.json", dir / "new.json"));  // neither exists yet
  fs::current_path(cwd);
  EXPECT_FALSE(same_file(dir / "scene.glb", dir / "other.glb"));
  EXPECT_FALSE(same_file(dir / "a.json", dir / "b.json"));
}

TEST(DistinctFiles, OutputsMustDifferAndStreamsAreExempt) {
  const fs::path dir = test::fresh_temp_dir("distinct-out");
  const std::string m = refusal({}, {{"-o", dir / "x.glb"}, {"--report", dir / "y.json"}, {"--save-project", dir / "x.glb"}});
  EXPECT_NE(m.find("-o " + (dir / "x.glb").string() + " and --save-project"), std::string::npos) << m;
  EXPECT_EQ(refusal({{"the input", dir / "in.glb"}}, {{"-o", dir / "x.glb"}, {"--report", dir / "y.json"}, {"--pattern", ""}}), "");
  // Written, not replaced: /dev/null may take several outputs; stdout only one.
  EXPECT_EQ(refusal({}, {{"-o", "/dev/null"}, {"--report", "/dev/null"}}), "");
  EXPECT_EQ(refusal({}, {{"-o", "-"}, {"--report", "/dev/null"}}), "");
  EXPECT_NE(refusal({}, {{"--json", "-"}, {"--overlay", "-"}}).find("only one result can go to stdout"), std::string::npos);
}

}  // namespace
}  // namespace fissure
