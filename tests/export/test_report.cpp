// The comparison report library (report/report.hpp) on tiny synthetic documents: page count and
// pagination, file naming, PDF/SVG/PNG structure, byte-identical output, grey mapping, and
// validation naming the problem.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "core/errors/error.hpp"
#include "core/image/image_io.hpp"
#include "report/report.hpp"
#include "report/report_draw.hpp"
#include "report/report_pages.hpp"
#include "tests/support/external_tool.hpp"

using namespace pinmask;
using pinmask::test::have_tool;

namespace {

ReportPanel panel(const std::string& caption, Plane values, double lo, double hi) {
    ReportPanel p;
    p.caption = caption;
    p.values = std::move(values);
    p.lo = lo;
    p.hi = hi;
    p.scale = std::to_string(p.values.rows()) + " x " + std::to_string(p.values.cols()) + " px";
    p.notes = {"PSNR 12.3 dB", "SSIM 0.456"};
    return p;
}

// A title page with `rows` table rows and `masks` mask pages of a few odd/prime/power-of-two
// sized panels.
ReportDocument tiny_document(int rows, int masks) {
    ReportDocument d;
    d.title = "pinmask compare: test";
    d.lines = {"camera: a test camera", "settings: none"};
    d.table.headers = {"mask", "K", "PSNR"};
    d.table.units = {"", "", "dB"};
    for (int r = 0; r < rows; ++r)
        d.table.rows.push_back({"mask " + std::to_string(r), std::to_string(r), "1.5"});
    d.notes = {"K: pinholes.", "PSNR: 10 log10(1 / MSE)."};
    for (int m = 0; m < masks; ++m) {
        ReportMaskPage p;
        p.title = "mask " + std::to_string(m);
        p.lines = {"a line"};
        Plane ramp(7, 7);
        for (int r = 0; r < 7; ++r)
            for (int c = 0; c < 7; ++c) ramp(r, c) = r * 7 + c;
        p.panels.push_back(panel("ramp 7 x 7", ramp, 0, 48));
        p.panels.push_back(panel("ones 8 x 8", Plane::Ones(8, 8), 0, 2));
        p.panels.push_back(panel("wide 5 x 13", Plane::Zero(5, 13), -1, 1));
        p.panels.push_back(panel("log 16 x 16", Plane::Constant(16, 16, -INFINITY), -6, 0));
        p.panels.push_back(panel("single pixel", Plane::Constant(1, 1, 0.5), 0, 1));
        d.pages.push_back(p);
    }
    return d;
}

std::size_t count(const std::string& hay, const std::string& needle) {
    std::size_t n = 0;
    for (std::size_t i = hay.find(needle); i != std::string::npos; i = hay.find(needle, i + 1)) ++n;
    return n;
}

// Pages of a PDF counted from its page objects ("/Type /Page" but not "/Type /Pages").
std::size_t pdf_pages(const std::string& pdf) {
    return count(pdf, "/Type /Page") - count(pdf, "/Type /Pages");
}

// Pure black pixels of an RGB PNG page (text and rules are dark grey, never pure black).
long long black_pixels(const std::string& png_bytes, const std::filesystem::path& tmp) {
    std::ofstream(tmp, std::ios::binary) << png_bytes;
    const Image img = read_image(tmp).image;
    long long n = 0;
    for (int r = 0; r < img.rows(); ++r)
        for (int c = 0; c < img.cols(); ++c) {
            bool black = true;
            for (const Plane& ch : img.channels) black = black && ch(r, c) == 0.0;
            n += black ? 1 : 0;
        }
    return n;
}

}  // namespace

TEST_CASE("report: page count is the table pages plus one page per mask") {
    CHECK(report_page_count(tiny_document(2, 0)) == 1);
    CHECK(report_page_count(tiny_document(2, 3)) == 4);
    CHECK(report_page_count(tiny_document(0, 1)) == 2);  // a table with no rows still has a page
    // 200 rows at most ~40 per page continue on further pages, each row on exactly one page.
    const ReportDocument big = tiny_document(200, 1);
    const auto pages = report_pages::plan_table_pages(big);
    REQUIRE(pages.size() >= 4);
    std::size_t next = 0;
    for (const auto& p : pages) {
        REQUIRE(p.has_table);
        CHECK(p.row_begin == next);
        CHECK(p.row_end > p.row_begin);
        next = p.row_end;
    }
    CHECK(next == 200);
    CHECK(pages.back().note_end == 2);  // both notes placed, after the last row
    CHECK(report_page_count(big) == static_cast<int>(pages.size()) + 1);
}

TEST_CASE("report: PDF is one file of all pages, byte-identical when rendered twice") {
    const ReportDocument d = tiny_document(3, 2);
    const std::string a = report_pdf(d), b = report_pdf(d);
    CHECK(a.rfind("%PDF-", 0) == 0);
    CHECK(a.find("%%EOF") != std::string::npos);
    CHECK(pdf_pages(a) == 3);
    CHECK(a == b);
    CHECK(a.find("/CreationDate (20000101000000Z)") != std::string::npos);  // pinned
    if (!have_tool("pdfinfo -v")) {
        MESSAGE("skipped pdfinfo cross-check: poppler-utils is not installed");
        return;
    }
    const auto dir = std::filesystem::temp_directory_path() / "pinmask-test-report-pdf";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "r.pdf", std::ios::binary) << a;
    const std::string out = (dir / "info.txt").string();
    REQUIRE(std::system(("pdfinfo " + (dir / "r.pdf").string() + " >" + out).c_str()) == 0);
    std::ifstream in(out);
    std::string line, pages;
    while (std::getline(in, line))
        if (line.rfind("Pages:", 0) == 0) pages = line;
    CHECK(pages.find(" 3") != std::string::npos);
    std::filesystem::remove_all(dir);
}

TEST_CASE("report: SVG pages are one well-formed file per page, renumbered ids, deterministic") {
    const ReportDocument d = tiny_document(3, 2);
    const auto a = report_svg_pages(d);
    const auto b = report_svg_pages(d);  // Cairo's process-wide ids have moved on by now
    REQUIRE(a.size() == 3);
    CHECK(a == b);
    for (const auto& svg : a) {
        CHECK(svg.rfind("<?xml", 0) == 0);
        CHECK(svg.find("</svg>") != std::string::npos);
        CHECK(svg.find("width=\"841.89pt\"") != std::string::npos);
    }
    // A mask page embeds 5 panel images and 5 colour-bar ramps: ids 1..10 in order.
    CHECK(a[1].find("id=\"image1\"") != std::string::npos);
    CHECK(a[1].find("id=\"image10\"") != std::string::npos);
    CHECK(a[1].find("id=\"image11\"") == std::string::npos);
    if (!have_tool("xmllint --version")) {
        MESSAGE("skipped xmllint check: libxml2-utils is not installed");
        return;
    }
    const auto dir = std::filesystem::temp_directory_path() / "pinmask-test-report-svg";
    std::filesystem::create_directories(dir);
    for (std::size_t i = 0; i < a.size(); ++i) {
        const auto f = dir / ("p" + std::to_string(i) + ".svg");
        std::ofstream(f, std::ios::binary) << a[i];
        CHECK(std::system(("xmllint --noout " + f.string() + " 2>/dev/null").c_str()) == 0);
    }
    std::filesystem::remove_all(dir);
}

TEST_CASE("report: PNG pages have the page size at the resolution and are deterministic") {
    const ReportDocument d = tiny_document(1, 1);
    const auto a = report_png_pages(d, 1.0);
    REQUIRE(a.size() == 2);
    CHECK(a == report_png_pages(d, 1.0));
    const auto dir = std::filesystem::temp_directory_path() / "pinmask-test-report-png";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "p.png", std::ios::binary) << a[1];
    const Image img = read_image(dir / "p.png").image;
    CHECK(img.cols() == 842);  // ceil(841.89 pt * 1 px/pt)
    CHECK(img.rows() == 596);  // ceil(595.28)
    std::filesystem::remove_all(dir);
    CHECK_THROWS_AS(report_png_pages(d, 0.0), InvalidInput);
    CHECK_THROWS_AS(report_png_pages(d, 9.0), InvalidInput);
}

TEST_CASE("report: grey levels are the clipped linear map of the display range") {
    using report_draw::grey_level;
    CHECK(grey_level(0.0, 0.0, 1.0) == 0);
    CHECK(grey_level(1.0, 0.0, 1.0) == 255);
    CHECK(grey_level(0.5, 0.0, 1.0) == 128);  // 127.5 rounds half away from zero
    CHECK(grey_level(-3.0, -6.0, 0.0) == 128);
    CHECK(grey_level(7.0, 0.0, 1.0) == 255);
    CHECK(grey_level(-7.0, 0.0, 1.0) == 0);
    CHECK(grey_level(-INFINITY, -6.0, 0.0) == 0);
    CHECK(grey_level(INFINITY, -6.0, 0.0) == 255);
    for (int k = 0; k <= 255; ++k) CHECK(grey_level(k / 255.0, 0.0, 1.0) == k);
}

TEST_CASE("report: panel pixels reach the page (black area of a checkerboard is half)") {
    // One page with one colour-bar-free panel; pure black pixels on the page come only from the
    // panel image (ink is dark grey). A 2 x 2 checkerboard is drawn as exactly half black.
    auto page_with = [](const Plane& values) {
        ReportDocument d;
        d.title = "t";
        d.table.headers = {"a"};
        ReportMaskPage p;
        p.title = "p";
        ReportPanel q;
        q.values = values;
        q.colorbar = false;
        p.panels.push_back(q);
        d.pages.push_back(p);
        return report_png_pages(d, 1.0).back();
    };
    const auto tmp = std::filesystem::temp_directory_path() / "pinmask-test-report-black.png";
    Plane checker(2, 2);
    checker << 0, 1, 1, 0;
    const long long all = black_pixels(page_with(Plane::Zero(2, 2)), tmp);
    const long long half = black_pixels(page_with(checker), tmp);
    const long long none = black_pixels(page_with(Plane::Ones(2, 2)), tmp);
    std::filesystem::remove(tmp);
    CHECK(all > 100 * 100);  // the single panel fills most of the page height
    CHECK(none == 0);
    // Half the squares, give or take the antialiased row and column where the squares meet.
    const double ratio = static_cast<double>(half) / static_cast<double>(all);
    constexpr double kEdgeTolerance = 0.02;  // one antialiased pixel line of ~500 per side
    CHECK(std::fabs(ratio - 0.5) <= kEdgeTolerance);
}

TEST_CASE("report: file names, formats and validation") {
    CHECK(report_format("a/r.PDF", "--report") == ReportFormat::kPdf);
    CHECK(report_format("r.svg", "--report") == ReportFormat::kSvg);
    CHECK(report_format("r.png", "--report") == ReportFormat::kPng);
    CHECK_THROWS_WITH_AS(report_format("r.jpg", "--report"), doctest::Contains("--report"),
                         InvalidInput);
    CHECK(report_file_paths("d/r.pdf", 3) == std::vector<std::filesystem::path>{"d/r.pdf"});
    CHECK(report_file_paths("d/r.svg", 2) ==
          std::vector<std::filesystem::path>{"d/r-1.svg", "d/r-2.svg"});
    const auto files = render_report(tiny_document(1, 2), "d/rep.png");
    REQUIRE(files.size() == 3);
    CHECK(files[2].first == std::filesystem::path("d/rep-3.png"));
    CHECK(files[2].second.rfind("\x89PNG", 0) == 0);

    ReportDocument d = tiny_document(2, 1);
    d.table.rows[1].pop_back();
    CHECK_THROWS_WITH_AS(validate(d), doctest::Contains("row 2"), InvalidInput);
    d = tiny_document(2, 1);
    d.pages[0].panels[1].values(0, 0) = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_WITH_AS(report_pdf(d), doctest::Contains("panel 2"), InvalidInput);
    d = tiny_document(2, 1);
    d.pages[0].panels[0].hi = d.pages[0].panels[0].lo;
    CHECK_THROWS_WITH_AS(validate(d), doctest::Contains("lo < hi"), InvalidInput);
    d = tiny_document(2, 1);
    d.pages[0].panels.clear();
    CHECK_THROWS_AS(validate(d), InvalidInput);
    d = tiny_document(2, 1);
    d.title.clear();
    CHECK_THROWS_AS(validate(d), InvalidInput);
}
