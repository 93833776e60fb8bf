// overload_note (fracture/overload.hpp): said when most of the body starts past its resistance,
// silent for a load that over-stresses only the region it strikes.
#include "fissure/fracture/overload.hpp"

#include <gtest/gtest.h>

namespace fissure {
namespace {

// n tets, the first `over` in uniaxial tension at 2·R_cm along x, the others unstressed.
StressField field(int n, int over, double resistance) {
  StressField s = StressField::Zero(n, 6);
  for (int t = 0; t < over; ++t) s(t, 0) = 2.0 * resistance;
  return s;
}

TEST(Overload, SaidWhenMostTetsStartPastTheResistance) {
  FractureParams p;
  const auto note = overload_note(field(100, 97, p.resistance_mean), p);
  ASSERT_TRUE(note.has_value());
  EXPECT_NE(note->find("97 % of the tets"), std::string::npos) << *note;
  EXPECT_NE(note->find("newtons"), std::string::npos) << *note;
}

TEST(Overload, SilentForAStrikeOnPartOfTheBody) {
  FractureParams p;
  EXPECT_FALSE(overload_note(field(100, 50, p.resistance_mean), p).has_value());  // half is not most
  EXPECT_FALSE(overload_note(field(100, 0, p.resistance_mean), p).has_value());
  // Compression is not over the (tensile) resistance (1e12 Pa: far past any material, and within
  // what the closed-form λ_max resolves next to zero).
  StressField c = field(100, 0, p.resistance_mean);
  c.col(2).setConstant(-1e12);
  EXPECT_FALSE(overload_note(c, p).has_value());
  EXPECT_FALSE(overload_note(StressField(0, 6), p).has_value());
}

}  // namespace
}  // namespace fissure
