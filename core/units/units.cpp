#include "core/units/units.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/errors/error.hpp"

namespace pinmask {
namespace {

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
}

InvalidInput bad_token(std::string_view field, std::string_view token, const std::string& rule) {
    return invalid_field(std::string(field), "'" + std::string(token) + "'", rule);
}

// Splits "12.5mm" into 12.5 and "mm". Throws when there is no leading number.
std::pair<double, std::string_view> split_number(std::string_view token, std::string_view field,
                                                 const std::string& expected) {
    const std::string_view s = trim(token);
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (ec != std::errc() || s.empty()) {
        throw bad_token(field, token, "not a number" + expected);
    }
    if (!std::isfinite(value)) throw bad_token(field, token, "must be finite");
    return {value, trim(s.substr(static_cast<std::size_t>(ptr - s.data())))};
}

double scaled(std::string_view token, std::string_view field,
              const std::vector<std::pair<std::string_view, double>>& suffixes,
              const std::string& expected) {
    const auto [value, suffix] = split_number(token, field, expected);
    for (const auto& [name, factor] : suffixes) {
        if (suffix != name) continue;
        // A finite number times its unit can still overflow ("11e307h"): refuse it here rather
        // than hand an infinity to a caller that asked for a finite value.
        const double result = value * factor;
        if (!std::isfinite(result)) throw bad_token(field, token, "out of range");
        return result;
    }
    throw bad_token(field, token, "unknown unit '" + std::string(suffix) + "'" + expected);
}

}  // namespace

double parse_length_m(std::string_view token, std::string_view field, AllowInfinity allow_inf) {
    const std::string_view t = trim(token);
    if (t == "inf" || t == "infinity" || t == "Inf") {
        if (allow_inf == AllowInfinity::kYes) return std::numeric_limits<double>::infinity();
        throw bad_token(field, token, "infinity is not allowed here");
    }
    static const std::vector<std::pair<std::string_view, double>> kLength = {
        {"", 1.0},    {"m", 1.0},          {"cm", 1e-2}, {"mm", 1e-3},
        {"um", 1e-6}, {"\xC2\xB5m", 1e-6}, {"nm", 1e-9}};
    return scaled(token, field, kLength, " (expected a length such as 440um, 55mm, 6m, 550nm)");
}

double parse_duration_s(std::string_view token, std::string_view field) {
    static const std::vector<std::pair<std::string_view, double>> kTime = {
        {"", 1.0}, {"s", 1.0}, {"ms", 1e-3}, {"min", 60.0}, {"h", 3600.0}};
    return scaled(token, field, kTime, " (expected a duration such as 20s, 500ms, 2min)");
}

double parse_number(std::string_view token, std::string_view field) {
    const auto [value, rest] = split_number(token, field, "");
    if (!rest.empty()) throw bad_token(field, token, "unexpected text after the number");
    return value;
}

Size2 parse_size(std::string_view token, std::string_view field) {
    const std::string_view s = trim(token);
    const auto x = s.find('x');
    if (x == std::string_view::npos) throw bad_token(field, token, "expected WIDTHxHEIGHT");
    int w = 0, h = 0;
    const auto a = std::from_chars(s.data(), s.data() + x, w);
    const auto b = std::from_chars(s.data() + x + 1, s.data() + s.size(), h);
    if (a.ec != std::errc() || a.ptr != s.data() + x || b.ec != std::errc() ||
        b.ptr != s.data() + s.size()) {
        throw bad_token(field, token, "expected WIDTHxHEIGHT with whole numbers, e.g. 720x480");
    }
    if (w < 1 || h < 1) throw bad_token(field, token, "width and height must be >= 1");
    return {w, h};
}

std::string format_length(double metres) {
    if (std::isinf(metres)) return "inf";
    const double a = std::fabs(metres);
    char buf[64];
    if (a >= 1.0 || a == 0.0) {
        std::snprintf(buf, sizeof buf, "%.4g m", metres);
    } else if (a >= 1e-3) {
        std::snprintf(buf, sizeof buf, "%.4g mm", metres * 1e3);
    } else if (a >= 1e-6) {
        std::snprintf(buf, sizeof buf, "%.4g um", metres * 1e6);
    } else {
        std::snprintf(buf, sizeof buf, "%.4g nm", metres * 1e9);
    }
    return buf;
}

std::string readable_numbers(const std::string& m) {
    std::string out;
    out.reserve(m.size());
    const auto digit = [&](std::size_t i) { return i < m.size() && m[i] >= '0' && m[i] <= '9'; };
    const auto word = [&](std::size_t i) {
        return i < m.size() && (std::isalnum(static_cast<unsigned char>(m[i])) || m[i] == '_');
    };
    std::size_t i = 0;
    while (i < m.size()) {
        if (!digit(i) || (i > 0 && (word(i - 1) || m[i - 1] == '.'))) {
            out += m[i++];
            continue;
        }
        std::size_t j = i;
        while (digit(j)) ++j;
        const std::size_t int_digits = j - i;
        std::size_t end = j;
        bool fixed6 = false;
        if (j < m.size() && m[j] == '.') {
            std::size_t k = j + 1;
            while (digit(k)) ++k;
            fixed6 = k - j - 1 == 6;
            if (k > j + 1) end = k;
        }
        if (!word(end) && ((int_digits >= 16 && fixed6) || int_digits >= 20)) {
            char buf[32];
            std::snprintf(buf, sizeof buf, "%.6g",
                          std::strtod(m.substr(i, end - i).c_str(), nullptr));
            out += buf;
        } else {
            out.append(m, i, end - i);
        }
        i = end;
    }
    return out;
}

}  // namespace pinmask
