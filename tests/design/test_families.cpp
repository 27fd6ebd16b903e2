// Pattern families: MURA (hand-checked p = 5, the balanced-correlation property by a direct
// periodic sum), the paper's geometry, and family names.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "core/errors/error.hpp"
#include "design/pattern/exclusion_grid.hpp"
#include "design/pattern/families.hpp"
#include "design/pattern/mura.hpp"

using namespace pinmask;
using doctest::Contains;

namespace {

std::vector<int> dense(const Pattern& p) {
    std::vector<int> a(static_cast<std::size_t>(p.n) * p.n, 0);
    for (const Cell& c : p.pinholes) a[static_cast<std::size_t>(c.row) * p.n + c.col] = 1;
    return a;
}

}  // namespace

TEST_CASE("MURA p = 5 matches the hand-built array") {
    // Quadratic residues mod 5: {1, 4}, so C = (-, +1, -1, -1, +1). Row 0 closed, column 0
    // open below it, A(i, j) = [C_i C_j = +1] elsewhere.
    const std::vector<int> expected = {
        0, 0, 0, 0, 0,  //
        1, 1, 0, 0, 1,  //
        1, 0, 1, 1, 0,  //
        1, 0, 1, 1, 0,  //
        1, 1, 0, 0, 1,  //
    };
    const Pattern p = mura_pattern(5);
    CHECK(p.n == 5);
    CHECK(dense(p) == expected);
    CHECK(p.pinholes.size() == 12);
}

TEST_CASE("MURA periodic correlation with its decoding array is a delta") {
    for (const int p : {5, 13, 17, 29}) {
        CAPTURE(p);
        const auto a = dense(mura_pattern(p));
        const auto g = mura_decoding_array(p);
        CHECK(std::count(a.begin(), a.end(), 1) == (p * p - 1) / 2);
        // Direct O(p^4) periodic sum: R(i, j) = sum_kl A(k, l) G(k + i, l + j).
        for (int i = 0; i < p; ++i) {
            for (int j = 0; j < p; ++j) {
                long long r = 0;
                for (int k = 0; k < p; ++k) {
                    for (int l = 0; l < p; ++l) {
                        r += a[static_cast<std::size_t>(k) * p + l] *
                             g[static_cast<std::size_t>((k + i) % p) * p + (l + j) % p];
                    }
                }
                CAPTURE(i);
                CAPTURE(j);
                CHECK(r == (i == 0 && j == 0 ? (p * p - 1) / 2 : 0));
            }
        }
    }
}

TEST_CASE("MURA breaks spacing 2 but not spacing 1") {
    for (const int p : {5, 13, 17}) {
        CAPTURE(p);
        Pattern m = mura_pattern(p, 2.0);
        CHECK_FALSE(spacing_violations(m).empty());
        CHECK_THROWS_AS(validate(m), InvalidInput);
        CHECK_NOTHROW(validate(m, /*allow_spacing_violations=*/true));
        m.min_spacing_cells = 1.0;
        CHECK(spacing_violations(m).empty());
    }
}

TEST_CASE("counting violations agrees with listing them, small tori included") {
    for (const int p : {5, 13, 17, 29}) {
        for (const double s : {0.0, 1.0, 1.5, 2.0, 3.0, 4.5, 7.0}) {
            CAPTURE(p);
            CAPTURE(s);
            const Pattern m = mura_pattern(p, s);
            CHECK(count_spacing_violations(m) == spacing_violations(m).size());
        }
    }
}

TEST_CASE("MURA orders must be primes 4m + 1") {
    for (const int p : {-5, 0, 1, 2, 3, 7, 9, 11, 15, 21, 25, 4097}) {
        CAPTURE(p);
        CHECK_THROWS_WITH_AS(mura_pattern(p), Contains("prime order p = 4m + 1"), InvalidInput);
        CHECK_THROWS_AS(mura_decoding_array(p), InvalidInput);
    }
    // is_prime against a sieve.
    constexpr int kLimit = 2000;
    std::vector<bool> composite(kLimit + 1, false);
    for (int i = 2; i * i <= kLimit; ++i) {
        for (int j = i * i; j <= kLimit; j += i) composite[j] = true;
    }
    for (int v = -3; v <= kLimit; ++v) {
        CAPTURE(v);
        CHECK(is_prime(v) == (v >= 2 && !composite[v]));
    }
}

TEST_CASE("paper family: 16 x 16, 20 pinholes, 2 x 2 tiles, spacing 2, seeded") {
    std::mt19937_64 a(7), b(7), c(8);
    const Pattern p = paper_pattern(a);
    CHECK(p.n == 16);
    CHECK(p.pinholes.size() == 20);
    CHECK(p.tiles_rows == 2);
    CHECK(p.tiles_cols == 2);
    CHECK(p.min_spacing_cells == 2.0);
    CHECK_NOTHROW(validate(p));
    CHECK(paper_pattern(b).pinholes == p.pinholes);
    CHECK(paper_pattern(c).pinholes != p.pinholes);
}

TEST_CASE("family names") {
    CHECK(parse_family("random") == Family::kRandom);
    CHECK(parse_family("paper") == Family::kPaper);
    CHECK(parse_family("mura") == Family::kMura);
    for (const Family f : {Family::kRandom, Family::kPaper, Family::kMura}) {
        CHECK(parse_family(family_name(f)) == f);
    }
    CHECK_THROWS_WITH_AS(parse_family("ura"), Contains("rectangular"), InvalidInput);
    CHECK_THROWS_WITH_AS(parse_family("hadamard"), Contains("random, paper, mura"), InvalidInput);
}
