#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <functional>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

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


int count_entries(const fs::path& dir) {
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++files;
  return files;
}

// A write through a symbolic link goes to the file the link points to, atomically, and the link
// stays a link: the old behaviour renamed the temporary file over the link itself.
TEST(AtomicFile, WritesThroughSymlinksAndKeepsThem) {
  const fs::path dir = test::fresh_temp_dir("atomic-link");
  fs::create_directory(dir / "real");
  write_file_atomically(dir / "real" / "data.txt", "old");
  fs::create_symlink("real/data.txt", dir / "link.txt");          // relative target
  fs::create_symlink(dir / "link.txt", dir / "link-to-link.txt");  // a chain
  write_file_atomically(dir / "link-to-link.txt", "new");
  EXPECT_TRUE(fs::is_symlink(dir / "link.txt"));
  EXPECT_TRUE(fs::is_symlink(dir / "link-to-link.txt"));
  EXPECT_EQ(read_file(dir / "real" / "data.txt"), "new");
  // A dangling link: its target is created, the link kept.
  fs::create_symlink("real/later.txt", dir / "dangling.txt");
  write_atomically(dir / "dangling.txt", [](const fs::path& temp) { write_file_atomically(temp, "made"); });
  EXPECT_TRUE(fs::is_symlink(dir / "dangling.txt"));
  EXPECT_EQ(read_file(dir / "real" / "later.txt"), "made");
  EXPECT_EQ(count_entries(dir / "real"), 2);  // no temporary file left beside the target
  // A loop is refused with a message, not followed forever.
  fs::create_symlink(dir / "loop-b", dir / "loop-a");
  fs::create_symlink(dir / "loop-a", dir / "loop-b");
  EXPECT_THROW(write_file_atomically(dir / "loop-a", "x"), IoError);
}

TEST(AtomicFile, PreservesPermissionsOfTheReplacedFile) {
  const fs::path dir = test::fresh_temp_dir("atomic-mode");
  const fs::path target = dir / "script.sh";
  write_file_atomically(target, "#!/bin/sh\n");
  ASSERT_EQ(::chmod(target.c_str(), 0751), 0);
  write_file_atomically(target, "#!/bin/sh\necho hi\n");
  struct stat st {};
  ASSERT_EQ(::stat(target.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0751u);
}

// A file its owner made read-only stays as it is, also for root (who passes access() checks);
// the rename that replaces a file needs only the directory's permission, so it used to succeed.
TEST(AtomicFile, RefusesToReplaceAReadOnlyFile) {
  const fs::path dir = test::fresh_temp_dir("atomic-readonly");
  const fs::path target = dir / "kept.glb";
  write_file_atomically(target, "precious");
  ASSERT_EQ(::chmod(target.c_str(), 0444), 0);
  for (const auto& write : std::vector<std::function<void()>>{
           [&] { write_file_atomically(target, "lost"); }, [&] { check_output_path(target); },
           [&] { write_atomically(target, [](const fs::path& temp) { write_file_atomically(temp, "lost"); }); }}) {
    try {
      write();
      ADD_FAILURE() << "a read-only file was replaced";
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find(target.string() + ": is read-only"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(read_file(target), "precious");
  // Through a link, the file it points to is what is protected.
  fs::create_symlink(target, dir / "link.glb");
  EXPECT_THROW(write_file_atomically(dir / "link.glb", "lost"), IoError);
  EXPECT_EQ(read_file(target), "precious");
}

// Special files are written, never replaced: the old code renamed a regular file over
// /dev/full when run as root.
TEST(AtomicFile, WritesCharacterDevicesInPlace) {
  write_file_atomically("/dev/null", "discarded");
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  try {
    write_file_atomically("/dev/full", "no room");
    FAIL() << "a write to /dev/full must fail";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/full"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("space"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
  // A writer that needs a file name, aimed at a device: it writes a temporary file elsewhere.
  EXPECT_THROW(write_atomically("/dev/full", [](const fs::path& temp) { write_file_atomically(temp, "x"); }), IoError);
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
}

TEST(AtomicFile, WritesFifosInPlace) {
  const fs::path dir = test::fresh_temp_dir("atomic-fifo");
  const fs::path fifo = dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = read_file(fifo); });
  write_file_atomically(fifo, "through the pipe");
  reader.join();
  EXPECT_EQ(received, "through the pipe");
  EXPECT_EQ(fs::status(fifo).type(), fs::file_type::fifo);
  EXPECT_TRUE(is_stream_target(fifo));
  EXPECT_FALSE(is_stream_target(dir / "plain.txt"));
}

TEST(AtomicFile, DashIsStandardOutput) {
  EXPECT_TRUE(is_stream_target("-"));
  testing::internal::CaptureStdout();
  write_file_atomically("-", "to stdout\n");
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "to stdout\n");
}

TEST(AtomicFile, RefusesBlockDevicesAndDirectories) {
  const fs::path dir = test::fresh_temp_dir("atomic-refuse");
  EXPECT_THROW(check_output_path(dir), IoError);
  EXPECT_THROW(check_output_path(""), IoError);
  EXPECT_THROW(check_output_path(dir / "missing-dir" / "x.msh"), IoError);
  // Any block device the machine has (none in some containers).
  for (const auto& entry : fs::directory_iterator("/dev")) {
    std::error_code ec;
    if (!entry.is_block_file(ec)) continue;
    EXPECT_THROW(check_output_path(entry.path()), IoError) << entry.path();
    EXPECT_THROW(write_file_atomically(entry.path(), "x"), IoError) << entry.path();
    break;
  }
}

// A disk that fills up half way: simulated with RLIMIT_FSIZE in a child process (writes past
// the limit fail with EFBIG), so the test needs no root and no small filesystem. The previous
// content must survive and no temporary file may remain.
TEST(AtomicFile, FailedWriteLeavesThePreviousFile) {
  const fs::path dir = test::fresh_temp_dir("atomic-full");
  const fs::path target = dir / "result.msh";
  write_file_atomically(target, "previous complete content");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit{4096, 4096};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    try {
      write_file_atomically(target, std::string(100000, 'x'));
    } catch (const IoError& e) {
      const bool named = std::string(e.what()).find("result.msh") != std::string::npos;
      ::_exit(named ? 0 : 2);
    }
    ::_exit(1);  // the write must not succeed
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "1: the oversized write succeeded, 2: the error did not name the file";
  EXPECT_EQ(read_file(target), "previous complete content");
  EXPECT_EQ(count_entries(dir), 1);
}

}  // namespace
}  // namespace fissure
