// Numbers as text, the two ways messages and tables print them: `format_number` with a number
// of significant digits (iostream's default notation: 6 digits as in "%g", 17 to round-trip a
// double), and `format_cell` for table cells with a printf spec and "-" for NaN (no value).
#pragma once

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

namespace pinmask {

inline std::string format_number(double v, int significant = 6) {
    std::ostringstream s;
    s.precision(significant);
    s << v;
    return s.str();
}

inline std::string format_cell(double v, const char* printf_spec = "%.3f") {
    if (std::isnan(v)) return "-";
    char buf[64];
    std::snprintf(buf, sizeof buf, printf_spec, v);
    return buf;
}

}  // namespace pinmask
