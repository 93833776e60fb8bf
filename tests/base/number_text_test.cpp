#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace fissure {
namespace {

TEST(NumberText, FormatsSignificantDigits) {
  // std::to_string printed these as "0.000000" and "-0.000000".
  EXPECT_EQ(format_number(1e-7), "1e-07");
  EXPECT_EQ(format_number(-1.25e-18), "-1.25e-18");
  EXPECT_EQ(format_number(0.05), "0.05");
  EXPECT_EQ(format_number(-0.0), "0");  // a negated zero (a load force's x) reads as 0
  EXPECT_EQ(format_number(3e10), "3e+10");
  EXPECT_EQ(format_number(24000), "24000");
  EXPECT_EQ(format_number(1.0 / 3.0, 3), "0.333");
  EXPECT_EQ(format_number(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(format_number(-std::numeric_limits<double>::infinity()), "-inf");
  EXPECT_EQ(format_number(std::nan("")), "nan");
}

TEST(NumberText, ParsesLists) {
  EXPECT_EQ(parse_number_list("1,2.5,-3e2", "t"), (std::vector<double>{1, 2.5, -300}));
  EXPECT_EQ(parse_number_list(" 1 , +2 ", "t"), (std::vector<double>{1, 2}));
  EXPECT_EQ(parse_number_list("4", "t"), (std::vector<double>{4}));
}

std::string message_of(std::string_view text, std::size_t count = 0) {
  try {
    if (count) {
      parse_number_list(text, "--weights", count, "fragment,crack,junction");
    } else {
      parse_number_list(text, "load 'top=1,2,x'");
    }
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

TEST(NumberText, RefusesBadItemsNamingThem) {
  EXPECT_EQ(message_of("1,2,x"), "load 'top=1,2,x': 'x' is not a finite number");
  EXPECT_EQ(message_of("1,,2"), "load 'top=1,2,x': '' is not a finite number");
  EXPECT_EQ(message_of(""), "load 'top=1,2,x': '' is not a finite number");
  EXPECT_EQ(message_of("1,nan,2"), "load 'top=1,2,x': 'nan' is not a finite number");
  EXPECT_EQ(message_of("1,inf"), "load 'top=1,2,x': 'inf' is not a finite number");
  EXPECT_EQ(message_of("1e999"), "load 'top=1,2,x': '1e999' is not a finite number");
  EXPECT_EQ(message_of("1 2"), "load 'top=1,2,x': '1 2' is not a finite number");
  EXPECT_EQ(message_of("+-1"), "load 'top=1,2,x': '+-1' is not a finite number");
}

TEST(NumberText, CountsBeforeParsing) {
  // "--weights 1,1" was answered "expected three numbers x,y,z".
  EXPECT_EQ(message_of("1,1", 3), "--weights: expected 3 numbers fragment,crack,junction, got 2");
  EXPECT_EQ(message_of("1,1,1,1", 3), "--weights: expected 3 numbers fragment,crack,junction, got 4");
  EXPECT_EQ(message_of("1,x,1", 3), "--weights: 'x' is not a finite number");
  EXPECT_EQ(message_of("", 3), "--weights: expected 3 numbers fragment,crack,junction, got 0");
}

}  // namespace
}  // namespace fissure
