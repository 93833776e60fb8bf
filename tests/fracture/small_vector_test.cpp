// SmallVector (src/fracture/small_vector.hpp): in place up to N, on the heap beyond, with copies
// and moves that keep every element, for over-aligned Eigen types too.
#include "small_vector.hpp"

#include <Eigen/Core>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>

namespace fissure::detail {
namespace {

template <class V>
std::vector<int> contents(const V& v) {
  return std::vector<int>(v.begin(), v.end());
}

TEST(SmallVector, GrowsPastItsInlineCapacityKeepingTheElements) {
  SmallVector<int, 3> v;
  for (int i = 0; i < 20; ++i) v.push_back(i);
  ASSERT_EQ(v.size(), 20u);
  for (int i = 0; i < 20; ++i) EXPECT_EQ(v[static_cast<std::size_t>(i)], i);
  v.truncate(5);
  EXPECT_EQ(contents(v), (std::vector<int>{0, 1, 2, 3, 4}));
  // push_back of its own element while growing (reserve moves the storage).
  SmallVector<int, 2> w{7, 8};
  w.push_back(w[0]);
  EXPECT_EQ(contents(w), (std::vector<int>{7, 8, 7}));
}

TEST(SmallVector, CopiesAndMovesInPlaceAndOnTheHeap) {
  for (int n : {2, 9}) {  // in place (N = 4) and on the heap
    SmallVector<std::string, 4> a;
    for (int i = 0; i < n; ++i) a.push_back(std::string(30, static_cast<char>('a' + i)));  // strings that allocate
    SmallVector<std::string, 4> b = a;
    EXPECT_EQ(b.size(), a.size());
    EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin()));
    SmallVector<std::string, 4> c = std::move(a);
    EXPECT_TRUE(a.empty());
    EXPECT_TRUE(std::equal(b.begin(), b.end(), c.begin(), c.end()));
    a = c;  // a moved-from vector is usable
    c = std::move(b);
    EXPECT_TRUE(std::equal(a.begin(), a.end(), c.begin(), c.end()));
    c = c;  // self-assignment keeps it
    EXPECT_EQ(c.size(), static_cast<std::size_t>(n));
  }
}

TEST(SmallVector, HoldsOverAlignedEigenTypesAlignedAndIsASpan) {
  SmallVector<Eigen::Vector4d, 2> v;
  for (int i = 0; i < 7; ++i) {
    v.push_back(Eigen::Vector4d::Constant(i));
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % alignof(Eigen::Vector4d), 0u);
  }
  const std::span<const Eigen::Vector4d> s = v;
  ASSERT_EQ(s.size(), 7u);
  EXPECT_EQ(s[6](3), 6.0);
}

}  // namespace
}  // namespace fissure::detail
