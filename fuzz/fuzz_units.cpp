// Fuzzes unit parsing (core/units/units): the first byte picks the parser, the rest is the token.
// Accepted values must be what the contract says (finite unless infinity was allowed, sizes
// >= 1), and a length printed by format_length must parse back to within its 4 digits.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/errors/error.hpp"
#include "core/units/units.hpp"
#include "fuzz/fuzz_support.hpp"

namespace {

// format_length prints 4 significant digits ("%.4g"): the value read back is within half a unit
// in the 4th digit, 5e-4 relative, plus a few roundings of the unit scaling (1e-12 margin).
constexpr double kFormatRelTol = 5e-4 + 1e-12;

void check_length_round_trip(double metres) {
    using namespace pinmask;
    if (std::isinf(metres)) {
        if (format_length(metres) != "inf") fuzz::invariant_failed("format_length(inf)");
        return;
    }
    if (!std::isfinite(metres)) fuzz::invariant_failed("non-finite length accepted");
    // Subnormal values lose relative precision when scaled by the unit: no round-trip bound.
    if (metres != 0.0 && !std::isnormal(metres)) return;
    const double back = parse_length_m(format_length(metres), "round trip");
    if (std::fabs(back - metres) > kFormatRelTol * std::fabs(metres)) {
        fuzz::invariant_failed("format_length round trip");
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace pinmask;
    if (size == 0) return 0;
    const std::string_view token = fuzz::as_text(data + 1, size - 1);
    try {
        switch (data[0] % 5) {
            case 0:
                check_length_round_trip(parse_length_m(token, "fuzz"));
                break;
            case 1:
                check_length_round_trip(parse_length_m(token, "fuzz", AllowInfinity::kYes));
                break;
            case 2:
                // "11e307h" once scaled a finite number to +inf (found by this target; now
                // refused in core/units/units, regression test in tests/core/test_units.cpp).
                if (!std::isfinite(parse_duration_s(token, "fuzz"))) {
                    fuzz::invariant_failed("non-finite duration accepted");
                }
                break;
            case 3:
                if (!std::isfinite(parse_number(token, "fuzz"))) {
                    fuzz::invariant_failed("non-finite number accepted");
                }
                break;
            default: {
                const Size2 s = parse_size(token, "fuzz");
                if (s.cols < 1 || s.rows < 1) fuzz::invariant_failed("size below 1 accepted");
            }
        }
    } catch (const InvalidInput&) {
    }
    return 0;
}
