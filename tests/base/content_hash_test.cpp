#include "fissure/base/content_hash.hpp"
#include "fissure/base/rng.hpp"

#include <gtest/gtest.h>

namespace fissure {
namespace {

TEST(ContentHash, DeterministicAndSensitive) {
  Rng rng(50);
  Eigen::MatrixXd m(50, 3);
  for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = rng.uniform(-1.0, 1.0);
  const Hash128 h1 = ContentHasher().add(m).add("steel").add(std::int64_t{50}).finish();
  const Hash128 h2 = ContentHasher().add(m).add("steel").add(std::int64_t{50}).finish();
  EXPECT_EQ(h1, h2);
  Eigen::MatrixXd m2 = m;
  m2(17, 2) = std::nextafter(m2(17, 2), 2.0);  // one ulp
  EXPECT_NE(ContentHasher().add(m2).add("steel").add(std::int64_t{50}).finish(), h1);
  EXPECT_NE(ContentHasher().add(m).add("steel").add(std::int64_t{51}).finish(), h1);
  EXPECT_EQ(h1.hex().size(), 32u);
}

TEST(ContentHash, FramingSeparatesFields) {
  EXPECT_NE(ContentHasher().add("ab").add("c").finish(), ContentHasher().add("a").add("bc").finish());
  EXPECT_NE(ContentHasher().add(1.0).finish(), ContentHasher().add(std::int64_t{0x3ff0000000000000}).finish());
  // Same data, different shape.
  Eigen::MatrixXd a = Eigen::MatrixXd::Ones(2, 3), b = Eigen::MatrixXd::Ones(3, 2);
  EXPECT_NE(ContentHasher().add(a).finish(), ContentHasher().add(b).finish());
}

TEST(ContentHash, SignedZeroIsTheSameInput) {
  EXPECT_EQ(ContentHasher().add(0.0).finish(), ContentHasher().add(-0.0).finish());
}

}  // namespace
}  // namespace fissure
