#include "export/formats/decimal.hpp"

#include "core/errors/error.hpp"

namespace pinmask {
namespace {

constexpr std::int64_t kMaxUnits = 1'000'000'000'000'000;  // 10^15

InvalidInput bad(std::string_view what, std::string_view text, const std::string& rule) {
    return invalid_field(std::string(what), "'" + std::string(text.substr(0, 40)) + "'", rule);
}

}  // namespace

void append_scaled(std::string& out, std::int64_t v, int digits) {
    char buf[32];
    int n = 0;
    unsigned long long m =
        v < 0 ? 0ULL - static_cast<unsigned long long>(v) : static_cast<unsigned long long>(v);
    // Digits in reverse: fraction first, then the integer part.
    bool any_fraction = false;
    for (int d = 0; d < digits; ++d) {
        const int digit = int(m % 10);
        m /= 10;
        if (digit != 0 || any_fraction) {
            buf[n++] = char('0' + digit);
            any_fraction = true;
        }
    }
    if (any_fraction) buf[n++] = '.';
    do {
        buf[n++] = char('0' + m % 10);
        m /= 10;
    } while (m);
    if (v < 0) buf[n++] = '-';
    while (n) out.push_back(buf[--n]);
}

std::int64_t parse_scaled(std::string_view text, int digits, std::string_view what) {
    std::size_t i = 0;
    bool negative = false;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) negative = text[i++] == '-';
    std::int64_t units = 0;
    int int_digits = 0, frac_digits = 0;
    auto push = [&](char c) {
        units = units * 10 + (c - '0');
        if (units > kMaxUnits) throw bad(what, text, "magnitude too large");
    };
    while (i < text.size() && text[i] >= '0' && text[i] <= '9') {
        push(text[i++]);
        ++int_digits;
    }
    std::string_view extra;
    if (i < text.size() && text[i] == '.') {
        ++i;
        const std::size_t start = i;
        while (i < text.size() && text[i] >= '0' && text[i] <= '9') {
            if (frac_digits < digits) {
                push(text[i]);
                ++frac_digits;
            }
            ++i;
        }
        const std::size_t used = std::size_t(frac_digits);
        extra = text.substr(start + used, i - start - used);
    }
    if (i != text.size() || (int_digits == 0 && frac_digits == 0 && extra.empty()))
        throw bad(what, text, "is not a plain decimal number");
    for (; frac_digits < digits; ++frac_digits) push('0');
    if (!extra.empty()) {
        const std::string_view head = extra.substr(0, 3);
        if (head.find_first_not_of('0') == std::string_view::npos && head.size() == 3) {
            // within 0.001 unit below: keep
        } else if (head.size() == 3 && head.find_first_not_of('9') == std::string_view::npos) {
            if (++units > kMaxUnits) throw bad(what, text, "magnitude too large");
        } else if (extra.find_first_not_of('0') != std::string_view::npos) {
            throw bad(what, text, "is not on the 1e-" + std::to_string(digits) + " grid");
        }
    }
    return negative ? -units : units;
}

}  // namespace pinmask
