#include "design/pattern/mura.hpp"

#include <string>

#include "core/errors/error.hpp"

namespace pinmask {
namespace {

void check_order(int p) {
    if (p < 2 || p > kMaxGrid || !is_prime(p) || p % 4 != 1) {
        throw invalid_field("n", std::to_string(p),
                            "a MURA needs a prime order p = 4m + 1 (5, 13, 17, 29, 37, ...) "
                            "up to " +
                                std::to_string(kMaxGrid));
    }
}

// residue[i] = C_i: +1 for nonzero quadratic residues mod p, -1 otherwise (C_0 unused).
std::vector<int> residue_signs(int p) {
    std::vector<int> c(static_cast<std::size_t>(p), -1);
    for (long long x = 1; x < p; ++x) c[static_cast<std::size_t>((x * x) % p)] = 1;
    return c;
}

std::vector<int> mura_array(int p) {
    const auto c = residue_signs(p);
    std::vector<int> a(static_cast<std::size_t>(p) * p, 0);
    for (int i = 1; i < p; ++i) {
        a[static_cast<std::size_t>(i) * p] = 1;
        for (int j = 1; j < p; ++j) {
            a[static_cast<std::size_t>(i) * p + j] = c[i] * c[j] == 1 ? 1 : 0;
        }
    }
    return a;
}

}  // namespace

bool is_prime(int v) {
    if (v < 2) return false;
    for (int d = 2; static_cast<long long>(d) * d <= v; ++d) {
        if (v % d == 0) return false;
    }
    return true;
}

Pattern mura_pattern(int p, double min_spacing_cells, int tiles_rows, int tiles_cols) {
    check_order(p);
    const auto a = mura_array(p);
    Pattern out;
    out.n = p;
    out.tiles_rows = tiles_rows;
    out.tiles_cols = tiles_cols;
    out.min_spacing_cells = min_spacing_cells;
    for (int i = 0; i < p; ++i) {
        for (int j = 0; j < p; ++j) {
            if (a[static_cast<std::size_t>(i) * p + j]) out.pinholes.push_back({i, j});
        }
    }
    return out;
}

std::vector<int> mura_decoding_array(int p) {
    check_order(p);
    auto g = mura_array(p);
    for (int& v : g) v = 2 * v - 1;
    g[0] = 1;
    return g;
}

}  // namespace pinmask
