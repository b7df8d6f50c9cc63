#pragma once
// Physical units for input values: "2.5 m", "30 min", "1200 cfs", "1.8 g/cm^3", "0.5 cm^3/(N*s)".
//
// A unit expression is a product and quotient of symbols with integer powers: `kg/m^3`, `m3/s`,
// `N*s/m^2`, `cm^3/(N s)`. Each symbol has a factor to SI and a dimension (length, mass, time,
// angle). Conversion checks dimensions and names both units when they do not match.
#include <array>
#include <string>
#include <string_view>

namespace suite::units {

struct Unit {
  double to_si = 1.0;                  // value_in_si = value * to_si
  std::array<int, 4> dim{0, 0, 0, 0};  // powers of length, mass, time, angle
};

// Throws InputError with a message that says what was not understood.
Unit parse(std::string_view text);

// Converts `value` from unit `from` to unit `to`; throws InputError if the dimensions differ.
double convert(double value, std::string_view from, std::string_view to);

// "length/time" style description of a dimension, for error messages.
std::string describe(const std::array<int, 4>& dim);

}  // namespace suite::units
