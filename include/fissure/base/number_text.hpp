#pragma once
/// Numbers to and from text, the same way everywhere: messages print significant digits (never
/// std::to_string's fixed six decimals, which shows 1e-7 as "0.000000"), and every
/// comma-separated list of numbers (tile sizes, forces, selections, CLI triples) is parsed and
/// refused by one function.

#include <string>
#include <string_view>
#include <vector>

namespace fissure {

/// `value` with `significant_digits` significant digits, shortest form ("0.05", "1e-07",
/// "2.4e+10", "-3", "inf", "nan"). For messages and reports; files that must round-trip use
/// their own full-precision formatting.
std::string format_number(double value, int significant_digits = 6);

/// Parses "a,b,c" (blanks around items allowed) into finite numbers. Throws InvalidInput
/// "<context>: 'x' is not a finite number" naming the first bad item; an empty list or an empty
/// item ("1,,2") is bad too.
std::vector<double> parse_number_list(std::string_view text, std::string_view context);

/// The same, and the list must hold exactly `count` numbers: InvalidInput
/// "<context>: expected <count> numbers <names>, got <n>" otherwise (`names` describes them,
/// e.g. "fx,fy,fz (newtons)").
std::vector<double> parse_number_list(std::string_view text, std::string_view context, std::size_t count,
                                      std::string_view names);

}  // namespace fissure
