#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "core/errors/error.hpp"
#include "core/units/units.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;

// Decimal suffix scaling is one multiplication: exact to a couple of ulps.
constexpr double kScaleTol = 1e-15;

TEST_CASE("lengths with suffixes") {
    CHECK_CLOSE(parse_length_m("440um", "pinhole"), 440e-6, kScaleTol);
    CHECK_CLOSE(parse_length_m("440\xC2\xB5m", "pinhole"), 440e-6, kScaleTol);
    CHECK_CLOSE(parse_length_m("55mm", "f"), 0.055, kScaleTol);
    CHECK_CLOSE(parse_length_m("6m", "u"), 6.0, kScaleTol);
    CHECK_CLOSE(parse_length_m("550nm", "lambda"), 550e-9, kScaleTol);
    CHECK_CLOSE(parse_length_m("1.5cm", "x"), 0.015, kScaleTol);
    CHECK_CLOSE(parse_length_m("0.12", "x"), 0.12, kScaleTol);
    CHECK_CLOSE(parse_length_m("1e-3", "x"), 1e-3, kScaleTol);
    CHECK_CLOSE(parse_length_m(" 30 um ", "x"), 30e-6, kScaleTol);
    CHECK(std::isinf(parse_length_m("inf", "u", AllowInfinity::kYes)));
}

TEST_CASE("bad length tokens name the field and the token") {
    for (const std::string bad : {"440uu", "abc", "", "mm", "12 parsecs", "1e999", "inf", "nan"}) {
        try {
            parse_length_m(bad, "pinhole");
            FAIL("accepted '" << bad << "'");
        } catch (const InvalidInput& e) {
            const std::string msg = e.what();
            CHECK(msg.find("pinhole") != std::string::npos);
            CHECK(msg.find("'" + bad + "'") != std::string::npos);
        }
    }
}

TEST_CASE("durations, numbers and sizes") {
    CHECK(parse_duration_s("20s", "time") == 20.0);
    CHECK_CLOSE(parse_duration_s("500ms", "time"), 0.5, kScaleTol);
    CHECK(parse_duration_s("2min", "time") == 120.0);
    CHECK(parse_duration_s("3", "time") == 3.0);
    CHECK_THROWS_AS(parse_duration_s("3 fortnights", "time"), InvalidInput);
    // Regression (fuzz_units): a finite number times its unit overflowed to +inf.
    CHECK_THROWS_WITH_AS(parse_duration_s("11e307h", "time"), doctest::Contains("out of range"),
                         InvalidInput);
    CHECK_THROWS_AS(parse_duration_s("1e307min", "time"), InvalidInput);
    CHECK(parse_length_m("1e308mm", "size") == doctest::Approx(1e305));
    CHECK(parse_number("2.5", "spacing") == 2.5);
    CHECK_THROWS_AS(parse_number("2.5mm", "spacing"), InvalidInput);
    const Size2 s = parse_size("720x480", "sensor");
    CHECK(s.cols == 720);
    CHECK(s.rows == 480);
    for (const char* bad : {"720", "x480", "720x", "0x480", "-1x3", "7.5x3", "720x480x3"}) {
        CHECK_THROWS_AS(parse_size(bad, "sensor"), InvalidInput);
    }
}

TEST_CASE("format_length") {
    CHECK(format_length(440e-6) == "440 um");
    CHECK(format_length(0.055) == "55 mm");
    CHECK(format_length(6.0) == "6 m");
}

TEST_CASE("readable_numbers shows std::to_string's spelled-out doubles as %g, nothing else") {
    using pinmask::readable_numbers;
    CHECK(readable_numbers("spacing = " + std::to_string(1e300) + ": bad") ==
          "spacing = 1e+300: bad");
    CHECK(readable_numbers("v = " + std::to_string(-1e300)) == "v = -1e+300");
    CHECK(readable_numbers("preview of 123456789012345678901 x 3 px") ==
          "preview of 1.23457e+20 x 3 px");
    // Left alone: short numbers, to_string of ordinary values, hashes, digits inside words.
    for (const std::string same :
         {std::string("n = 1000000000: 12.500000"), std::string("hash 3940021234567890"),
          std::string("x1234567890123456789012y"), std::string("a.12345678901234567890"),
          std::string("")}) {
        CHECK(readable_numbers(same) == same);
    }
    // invalid_field applies it.
    const std::string msg = pinmask::invalid_field("--x", std::to_string(1e300), "r").what();
    CHECK(msg == "--x = 1e+300: r");
}
