// Exact decimal text for integer nanometres, shared by the text writers and readers: a value v
// in units of 10^-digits (digits = 3: nm written as micrometres; 6: nm as millimetres) is
// written with `digits` decimals and trailing zeros dropped, and parsed back exactly. No binary
// floating point is involved, so a written file reads back to the same integers.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace pinmask {

// Appends v / 10^digits in plain decimal ("-12.345", "7", "0.5"). 0 <= digits <= 9.
void append_scaled(std::string& out, std::int64_t v, int digits);

// Parses "[+-]digits[.digits]" (no exponent) as an integer count of 10^-digits units. Further
// decimals must be within 0.001 of a unit ("...000x" rounds down, "...999x" up), else the value
// is off the grid. Throws InvalidInput naming `what` for malformed text, off-grid values and
// magnitudes beyond 10^15 units.
std::int64_t parse_scaled(std::string_view text, int digits, std::string_view what);

}  // namespace pinmask
