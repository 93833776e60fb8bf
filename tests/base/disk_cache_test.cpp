// The on-disk cache's entries (disk_cache.hpp): a whole, matching entry reads back; anything else
// (another key, another version, a flipped byte, a truncation) reads as absent, never as a wrong
// payload; the directory is pruned least recently used first; concurrent writers of one key
// leave one whole entry.

#include "fissure/base/disk_cache.hpp"

#include "fissure/base/atomic_file.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <thread>
#include <vector>

namespace fissure {
namespace {

namespace fs = std::filesystem;

constexpr CacheEntryFormat kFormat{"FISSTEST", 3};

Hash128 key_of(const std::string& text) { return ContentHasher().add(text).finish(); }

TEST(DiskCache, AnEntryReadsBackOnlyUnderItsKeyAndVersion) {
  const fs::path dir = test::fresh_temp_dir("disk-cache-roundtrip") / "nested" / "cache";  // created on write
  const std::string payload("payload\0with zero", 17);
  ASSERT_EQ(write_cache_entry(dir, "a.bin", kFormat, key_of("a"), payload, 1 << 20), "");
  EXPECT_EQ(read_cache_entry(dir, "a.bin", kFormat, key_of("a")), payload);
  EXPECT_FALSE(read_cache_entry(dir, "a.bin", kFormat, key_of("b")));
  EXPECT_FALSE(read_cache_entry(dir, "a.bin", CacheEntryFormat{"FISSTEST", 4}, key_of("a")));
  EXPECT_FALSE(read_cache_entry(dir, "a.bin", CacheEntryFormat{"FISSOTHR", 3}, key_of("a")));
  EXPECT_FALSE(read_cache_entry(dir, "missing.bin", kFormat, key_of("a")));
  ASSERT_EQ(write_cache_entry(dir, "empty.bin", kFormat, key_of("e"), "", 1 << 20), "");
  EXPECT_EQ(read_cache_entry(dir, "empty.bin", kFormat, key_of("e")), std::string());
}

TEST(DiskCache, EveryDamagedOrTruncatedEntryReadsAsAbsent) {
  const fs::path dir = test::fresh_temp_dir("disk-cache-damage");
  const std::string payload = "0123456789abcdef0123456789abcdef";
  ASSERT_EQ(write_cache_entry(dir, "e.bin", kFormat, key_of("e"), payload, 1 << 20), "");
  const std::string whole = read_file(dir / "e.bin");
  for (std::size_t i = 0; i < whole.size(); ++i) {
    std::string bad = whole;
    bad[i] = static_cast<char>(bad[i] ^ 0x10);
    write_file_atomically(dir / "e.bin", bad);
    EXPECT_FALSE(read_cache_entry(dir, "e.bin", kFormat, key_of("e"))) << "byte " << i;
  }
  for (std::size_t n = 0; n < whole.size(); ++n) {
    write_file_atomically(dir / "e.bin", whole.substr(0, n));
    EXPECT_FALSE(read_cache_entry(dir, "e.bin", kFormat, key_of("e"))) << n << " bytes";
  }
  write_file_atomically(dir / "e.bin", whole);
  EXPECT_EQ(read_cache_entry(dir, "e.bin", kFormat, key_of("e")), payload);  // the loop did test damage
}

TEST(DiskCache, PruningRemovesTheLeastRecentlyUsedFirst) {
  const fs::path dir = test::fresh_temp_dir("disk-cache-prune");
  const std::string kb(1000, 'x');
  // Entries a, b, c, d written in that order, a second apart in their times; then a is read.
  const auto now = fs::file_time_type::clock::now();
  int age = 10;
  for (const char* name : {"a", "b", "c", "d"}) {
    ASSERT_EQ(write_cache_entry(dir, name, kFormat, key_of(name), kb, 1 << 20), "");
    fs::last_write_time(dir / name, now - std::chrono::seconds(age--));
  }
  ASSERT_TRUE(read_cache_entry(dir, "a", kFormat, key_of("a")));
  const std::uint64_t entry = fs::file_size(dir / "a");
  // Room for two entries: b and c, the least recently used, go; a (just read) and d stay.
  EXPECT_EQ(prune_cache(dir, 2 * entry + 10), 2 * entry);
  EXPECT_TRUE(fs::exists(dir / "a"));
  EXPECT_FALSE(fs::exists(dir / "b"));
  EXPECT_FALSE(fs::exists(dir / "c"));
  EXPECT_TRUE(fs::exists(dir / "d"));
  // `keep` survives even when it alone is over the cap; a write prunes to its cap.
  EXPECT_EQ(prune_cache(dir, 1, "d"), entry);
  EXPECT_TRUE(fs::exists(dir / "d"));
  ASSERT_EQ(write_cache_entry(dir, "e", kFormat, key_of("e"), kb, entry + 10), "");
  EXPECT_FALSE(fs::exists(dir / "d"));
  EXPECT_TRUE(fs::exists(dir / "e"));
}

TEST(DiskCache, ConcurrentWritersOfOneKeyLeaveOneWholeEntry) {
  const fs::path dir = test::fresh_temp_dir("disk-cache-race");
  const std::string payload(200000, 'p');
  std::vector<std::thread> writers;
  std::vector<std::string> problems(8);
  for (int t = 0; t < 8; ++t) {
    writers.emplace_back([&, t] {
      for (int i = 0; i < 5; ++i) {
        problems[static_cast<std::size_t>(t)] += write_cache_entry(dir, "k.bin", kFormat, key_of("k"), payload, 1 << 30);
        // A reader in between sees the whole entry or none, never a part.
        if (auto got = read_cache_entry(dir, "k.bin", kFormat, key_of("k"))) {
          if (*got != payload) problems[static_cast<std::size_t>(t)] += "a partial entry was read";
        }
      }
    });
  }
  for (std::thread& w : writers) w.join();
  for (const std::string& p : problems) EXPECT_EQ(p, "");
  EXPECT_EQ(read_cache_entry(dir, "k.bin", kFormat, key_of("k")), payload);
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file() ? 1 : 0;
  EXPECT_EQ(files, 1);  // no temporary file left behind
}

TEST(DiskCache, AnUnwritableDirectoryIsReportedNotThrown) {
  const fs::path dir = test::fresh_temp_dir("disk-cache-unwritable");
  write_file_atomically(dir / "file", "not a directory");
  const std::string problem = write_cache_entry(dir / "file" / "cache", "a", kFormat, key_of("a"), "x", 1 << 20);
  EXPECT_NE(problem.find((dir / "file").string()), std::string::npos) << problem;
}

TEST(DiskCache, TheSizeCapComesFromTheEnvironment) {
  ::setenv("FISSURE_CACHE_MAX_MB", "2", 1);
  EXPECT_EQ(default_cache_size_limit(), 2u << 20);
  ::setenv("FISSURE_CACHE_MAX_MB", "nonsense", 1);
  EXPECT_EQ(default_cache_size_limit(), std::uint64_t{4} << 30);
  ::unsetenv("FISSURE_CACHE_MAX_MB");
  EXPECT_EQ(default_cache_size_limit(), std::uint64_t{4} << 30);
}

}  // namespace
}  // namespace fissure
