// Unit parsing for command-line and file values. Lengths: a number with an optional suffix
// m, cm, mm, um (or µm), nm; a plain number is SI (metres). "inf" is accepted only where the
// caller allows it (object distance). Durations: s, ms, min, h; a plain number is seconds.
// Anything else throws InvalidInput naming the field and the offending token.
#pragma once

#include <string>
#include <string_view>

namespace pinmask {

enum class AllowInfinity { kNo, kYes };

// Length in metres. Examples: "440um" -> 4.4e-4, "55mm" -> 0.055, "6m" -> 6, "1e-3" -> 0.001.
double parse_length_m(std::string_view token, std::string_view field,
                      AllowInfinity allow_inf = AllowInfinity::kNo);

// Duration in seconds. Examples: "20s" -> 20, "500ms" -> 0.5, "2min" -> 120, "1h" -> 3600.
double parse_duration_s(std::string_view token, std::string_view field);

// A plain real number (no unit), finite.
double parse_number(std::string_view token, std::string_view field);

// "720x480" -> {720, 480} (width x height = cols x rows); both >= 1.
struct Size2 {
    int cols;
    int rows;
};
Size2 parse_size(std::string_view token, std::string_view field);

// Rewrites, in a message, every number std::to_string(double) spelled out in full (16 or more
// integer digits followed by ".dddddd", e.g. 1e300 as 301 digits) or any run of 20+ digits as
// %.6g ("1e+300"). Everything else is left as it is (hashes, small numbers). Applied by
// invalid_field and by the CLI to every error it prints.
std::string readable_numbers(const std::string& message);

// Formats a length for people: 4.4e-4 -> "440 um", 0.055 -> "55 mm".
std::string format_length(double metres);

}  // namespace pinmask
