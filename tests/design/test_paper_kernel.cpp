// The paper's Fig. 3b kernel: the table in the source against the shared CSV, and the PSF of a
// 16 x 16, K = 20 pattern against an independent upsampling (paper, Sec. 2.2).
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors/error.hpp"
#include "design/psf/kernel.hpp"
#include "design/psf/paper_kernel.hpp"
#include "design/psf/psf.hpp"
#include "tests/support/random_pattern.hpp"

using namespace pinmask;
namespace fs = std::filesystem;

namespace {

// The CSV and the source table both hold the printed four-decimal values: equal to rounding of
// the decimal-to-binary conversion.
constexpr double kTableTol = 1e-12;
// The PSF and the reference are sums of at most K = 20 products of normalised values; the
// requirement is agreement to 1e-6 (both ways of summing agree far better, ~1e-17).
constexpr double kPsfTol = 1e-6;

const fs::path kCsv = fs::path(PINMASK_SHARED_DIR) / "data" / "paper" / "fig3b-kernel.csv";

std::vector<double> read_csv(const fs::path& path) {
    std::ifstream in(path);
    std::vector<double> v;
    std::string line;
    while (std::getline(in, line)) {
        std::stringstream s(line);
        std::string cell;
        while (std::getline(s, cell, ',')) v.push_back(std::stod(cell));
    }
    return v;
}

// The paper's recipe written out for the test: upsample the 0/1 pattern by 8, replace each '1'
// by the 8 x 8 block (normalised), divide by K so the PSF sums to 1.
Plane upsampled_reference(const Pattern& p, const std::vector<double>& table) {
    double sum = 0;
    for (double t : table) sum += t;
    const int side = p.n * 8;
    Plane a = Plane::Zero(side, side);
    for (const Cell& c : p.pinholes) {
        for (int i = 0; i < 8; ++i) {
            for (int j = 0; j < 8; ++j) {
                a(c.row * 8 + i, c.col * 8 + j) += table[i * 8 + j] / sum / p.pinholes.size();
            }
        }
    }
    return a;
}

// min over cyclic shifts of max |a - roll(b)|.
double best_shift_error(const Plane& a, const Plane& b) {
    const Eigen::Index n = a.rows();
    double best = INFINITY;
    for (Eigen::Index dr = 0; dr < n; ++dr) {
        for (Eigen::Index dc = 0; dc < n; ++dc) {
            double worst = 0;
            for (Eigen::Index r = 0; r < n && worst < best; ++r) {
                for (Eigen::Index c = 0; c < n; ++c) {
                    worst = std::max(worst, std::fabs(a(r, c) - b((r + dr) % n, (c + dc) % n)));
                }
            }
            best = std::min(best, worst);
        }
    }
    return best;
}

}  // namespace

TEST_CASE("paper-fig3b: the source table equals the shared CSV (when present)") {
    const auto& table = paper_fig3b_table();
    if (!fs::exists(kCsv)) {
        MESSAGE("skipped: " << kCsv << " not present");
        return;
    }
    const std::vector<double> csv = read_csv(kCsv);
    REQUIRE(csv.size() == table.size());
    for (std::size_t i = 0; i < csv.size(); ++i) CHECK(std::fabs(csv[i] - table[i]) <= kTableTol);
}

TEST_CASE("paper-fig3b: normalised, symmetric, 8 x 8 at origin 0") {
    const Kernel k = make_kernel(paper_camera(), KernelSpec{"paper-fig3b", "", {}}, 8);
    CHECK(k.model == KernelModel::kPaperFig3b);
    REQUIRE(k.values.rows() == 8);
    REQUIRE(k.values.cols() == 8);
    CHECK(k.origin_row == 0);
    CHECK(k.origin_col == 0);
    CHECK(std::fabs(k.values.sum() - 1.0) <= 1e-14);
    for (int r = 0; r < 8; ++r) {
        for (int c = 0; c < 8; ++c) {
            CHECK(k.values(r, c) == k.values(c, r));
            CHECK(k.values(r, c) == k.values(7 - r, 7 - c));
        }
    }
    CHECK_THROWS_AS(make_kernel(paper_camera(), KernelSpec{"paper-fig3b", "", {}}, 16),
                    InvalidInput);
}

TEST_CASE("paper-fig3b: PSF of a 16 x 16, K = 20 mask = independent upsampling, to 1e-6") {
    const Pattern p = test::random_pattern(16, 20, 3);
    std::vector<double> table(paper_fig3b_table().begin(), paper_fig3b_table().end());
    if (fs::exists(kCsv)) table = read_csv(kCsv);  // the reference from the shared file itself
    const Plane ref = upsampled_reference(p, table);
    const Kernel k = make_kernel(paper_camera(), KernelSpec{"paper-fig3b", "", {}}, 8);
    for (PsfMethod method : {PsfMethod::kDirect, PsfMethod::kFourier}) {
        const Plane a = synthesize_psf(p, k, 8, method);
        REQUIRE(a.rows() == 128);
        CHECK(best_shift_error(a, ref) <= kPsfTol);
    }
}
