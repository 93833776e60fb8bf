#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

namespace fissure {
namespace {
namespace fs = std::filesystem;

TEST(AtomicFile, WritesAndReplaces) {
  const fs::path dir = test::fresh_temp_dir("atomic1");
  const fs::path target = dir / "out.txt";
  write_file_atomically(target, "first");
  EXPECT_EQ(read_file(target), "first");
  write_file_atomically(target, "second");
  EXPECT_EQ(read_file(target), "second");
  // No temporary files are left behind.
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);
}

TEST(AtomicFile, FailedWriterLeavesTargetIntact) {
  const fs::path dir = test::fresh_temp_dir("atomic2");
  const fs::path target = dir / "keep.txt";
  write_file_atomically(target, "precious");
  EXPECT_THROW(write_atomically(target,
                                [](const fs::path& temp) {
                                  write_file_atomically(temp, "partial");
                                  throw IoError("writer failed half way");
                                }),
               IoError);
  EXPECT_EQ(read_file(target), "precious");
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);
}

TEST(AtomicFile, ErrorsNameTheFile) {
  const fs::path dir = test::fresh_temp_dir("atomic3");
  try {
    write_file_atomically(dir / "no-such-dir" / "x.txt", "x");
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-dir"), std::string::npos) << e.what();
  }
  try {
    read_file(dir / "missing.msh");
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.msh"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_file(dir), IoError);
  EXPECT_THROW(write_file_atomically(dir, "x"), IoError);
}

}  // namespace
}  // namespace fissure
