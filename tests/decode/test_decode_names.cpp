// The name tables of decode (decode/solvers/decode_method.hpp, decode/solvers/decode_modes.hpp):
// every entry round-trips name -> value -> name, names are unique, an unknown name or an enum value
// outside the table is an error naming the field (never a fall-through to some default).
#include <doctest/doctest.h>

#include <set>
#include <string>

#include "core/errors/error.hpp"
#include "decode/solvers/decode_method.hpp"
#include "decode/solvers/decode_modes.hpp"

using namespace pinmask;

namespace {

template <class E, std::size_t N, class Parse, class Name>
void round_trip(const NameTable<E, N>& table, Parse parse, Name name, const char* field) {
    std::set<std::string> seen;
    for (const auto& [value, text] : table) {
        const E v = value;
        const std::string t = text;
        INFO(field << ": " << t);
        CHECK(seen.insert(t).second);  // one spelling per value, no name twice
        CHECK(parse(t) == v);
        CHECK(std::string(name(v)) == t);
        CHECK(parse_name(table, t, field) == v);
    }
    CHECK(seen.size() == N);
    CHECK_THROWS_WITH_AS(parse("no-such-name"), doctest::Contains("no-such-name"), InvalidInput);
    CHECK_THROWS_WITH_AS(name(static_cast<E>(99)), doctest::Contains("99"), InvalidInput);
}

}  // namespace

TEST_CASE("decode method names: one spelling each, round trip, unknown refused") {
    round_trip(
        kDecodeMethodNames, [](const std::string& s) { return parse_decode_method(s); },
        decode_method_name, "method");
    CHECK(kDecodeMethodNames.size() == kDecodeMethods.size());
    for (std::size_t i = 0; i < kDecodeMethods.size(); ++i)
        CHECK(kDecodeMethodNames[i].first == kDecodeMethods[i]);
    CHECK(decode_method_names() == "wiener | tikhonov | tv | tvqc | richardson-lucy");
    for (const char* other : {"rl", "RL", "tv-l2", "rl_iteration", "Wiener", ""}) {
        INFO(other);
        CHECK_THROWS_WITH_AS(parse_decode_method(other, "--method"), doctest::Contains("--method"),
                             InvalidInput);
    }
}

TEST_CASE("decode mode names: model, regulariser, background, normalize, precision") {
    round_trip(
        kConvModelNames, [](const std::string& s) { return parse_conv_model(s); }, conv_model_name,
        "model");
    round_trip(
        kRegulariserNames, [](const std::string& s) { return parse_regulariser(s); },
        regulariser_name, "regulariser");
    round_trip(
        kBackgroundModeNames,
        [](const std::string& s) { return parse_name(kBackgroundModeNames, s, "background"); },
        background_mode_name, "background");
    round_trip(
        kNormalizeModeNames, [](const std::string& s) { return parse_normalize_mode(s); },
        normalize_mode_name, "normalize");
    round_trip(
        kPrecisionNames, [](const std::string& s) { return parse_precision(s); }, precision_name,
        "precision");
    CHECK(names_of(kPrecisionNames) == "auto | single | double");
    CHECK(name_list(kConvModelNames) == std::vector<std::string>{"cyclic", "linear"});
}
