#include "export/formats/pdf_reader.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "core/errors/error.hpp"
#include "core/limits/resource_limits.hpp"

namespace pinmask {
namespace {

InvalidInput bad(const std::string& rule) { return InvalidInput("pdf: " + rule); }

// Page size agreement: the MediaBox is printed with a few decimals.
constexpr double kPageSizeTolerancePt = 0.01;
constexpr std::size_t kMaxOperands = 16;

bool is_delimiter(char c) {
    return std::isspace(static_cast<unsigned char>(c)) || c == '/' || c == '[' || c == ']' ||
           c == '<' || c == '>' || c == '(' || c == ')' || c == '%';
}

// Position of "N 0 obj" at the start of a line (or of the file); npos when absent.
std::size_t find_object(std::string_view pdf, long number) {
    const std::string key = std::to_string(number) + " 0 obj";
    for (std::size_t pos = pdf.find(key); pos != std::string_view::npos;
         pos = pdf.find(key, pos + 1)) {
        if (pos == 0 || pdf[pos - 1] == '\n' || pdf[pos - 1] == '\r') return pos + key.size();
    }
    return std::string_view::npos;
}

// The integer after `key` in `dict`, and whether it is an indirect reference "N 0 R".
bool dict_number(std::string_view dict, std::string_view key, long& value, bool& indirect) {
    std::size_t pos = dict.find(key);
    while (pos != std::string_view::npos && pos + key.size() < dict.size() &&
           !is_delimiter(dict[pos + key.size()]))
        pos = dict.find(key, pos + 1);
    if (pos == std::string_view::npos) return false;
    const std::string rest(dict.substr(pos + key.size(), 40));
    long a = 0, b = 0;
    char r = 0;
    indirect = std::sscanf(rest.c_str(), " %ld %ld %c", &a, &b, &r) == 3 && r == 'R';
    if (!indirect && std::sscanf(rest.c_str(), " %ld", &a) != 1) return false;
    value = a;
    return true;
}

std::string inflate_bytes(std::string_view in) {
    z_stream z{};
    if (inflateInit(&z) != Z_OK) throw RuntimeFailure("pdf: zlib inflateInit failed");
    std::string out;
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
    z.avail_in = static_cast<uInt>(in.size());
    std::array<char, 65536> buf;
    int rc = Z_OK;
    while (rc != Z_STREAM_END) {
        z.next_out = reinterpret_cast<Bytef*>(buf.data());
        z.avail_out = buf.size();
        rc = inflate(&z, Z_NO_FLUSH);
        if (rc != Z_OK && rc != Z_STREAM_END) {
            inflateEnd(&z);
            throw bad("the content stream does not inflate (zlib error " + std::to_string(rc) +
                      ")");
        }
        const std::size_t got = buf.size() - z.avail_out;
        if (got == 0 && rc != Z_STREAM_END && z.avail_in == 0) {
            inflateEnd(&z);
            throw bad("the content stream is truncated");
        }
        check_memory(double(out.size() + got) * 2.0, "PDF content stream");
        out.append(buf.data(), got);
    }
    inflateEnd(&z);
    return out;
}

// The page's content stream, inflated.
std::string page_content(std::string_view pdf, PdfPage& page) {
    std::size_t page_at = std::string_view::npos;
    for (std::size_t pos = pdf.find("/Type /Page"); pos != std::string_view::npos;
         pos = pdf.find("/Type /Page", pos + 1)) {
        if (pos + 11 < pdf.size() && pdf[pos + 11] == 's') continue;  // /Type /Pages
        if (page_at != std::string_view::npos) throw bad("more than one page");
        page_at = pos;
    }
    if (page_at == std::string_view::npos) throw bad("no /Type /Page object");
    const std::size_t dict_end = pdf.find(">>\nendobj", page_at);
    const std::string_view dict =
        pdf.substr(page_at, (dict_end == std::string_view::npos ? pdf.size() : dict_end) - page_at);
    const std::size_t mb = dict.find("/MediaBox");
    double box[4];
    if (mb == std::string_view::npos ||
        std::sscanf(std::string(dict.substr(mb + 9, 120)).c_str(), " [ %lf %lf %lf %lf", &box[0],
                    &box[1], &box[2], &box[3]) != 4)
        throw bad("the page has no readable /MediaBox");
    if (box[0] != 0 || box[1] != 0) throw bad("the /MediaBox does not start at 0 0");
    page.width_pt = box[2];
    page.height_pt = box[3];
    long contents = 0;
    bool indirect = false;
    if (!dict_number(dict, "/Contents", contents, indirect) || !indirect)
        throw bad("the page's /Contents is not one indirect stream (arrays are not supported)");
    const std::size_t obj = find_object(pdf, contents);
    if (obj == std::string_view::npos)
        throw bad("content object " + std::to_string(contents) + " not found");
    const std::size_t s = pdf.find("stream", obj);
    if (s == std::string_view::npos) throw bad("content object has no stream");
    const std::string_view sdict = pdf.substr(obj, s - obj);
    long length = 0;
    bool length_ref = false;
    if (!dict_number(sdict, "/Length", length, length_ref)) throw bad("stream without /Length");
    if (length_ref) {
        const std::size_t lo = find_object(pdf, length);
        long v = 0;
        if (lo == std::string_view::npos ||
            std::sscanf(std::string(pdf.substr(lo, 40)).c_str(), " %ld", &v) != 1)
            throw bad("stream /Length object " + std::to_string(length) + " not found");
        length = v;
    }
    std::size_t data = s + 6;
    if (data < pdf.size() && pdf[data] == '\r') ++data;
    if (data < pdf.size() && pdf[data] == '\n') ++data;
    if (length < 0 || data + std::size_t(length) > pdf.size())
        throw bad("stream /Length " + std::to_string(length) + " runs past the end of the file");
    const std::string_view raw = pdf.substr(data, std::size_t(length));
    const bool flate = sdict.find("/FlateDecode") != std::string_view::npos;
    if (!flate && sdict.find("/Filter") != std::string_view::npos)
        throw bad("content stream filter other than /FlateDecode");
    return flate ? inflate_bytes(raw) : std::string(raw);
}

struct Matrix {
    double a = 1, b = 0, c = 0, d = 1, e = 0, f = 0;
    PdfPoint apply(double x, double y) const { return {a * x + c * y + e, b * x + d * y + f}; }
    // m applied first, then this (PDF: cm sets CTM = m x CTM).
    Matrix after(const Matrix& m) const {
        return {m.a * a + m.b * c, m.a * b + m.b * d,     m.c * a + m.d * c,
                m.c * b + m.d * d, m.e * a + m.f * c + e, m.e * b + m.f * d + f};
    }
};

double seg_distance(const PdfPoint& p, const PdfPoint& a, const PdfPoint& b) {
    const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / l2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

// Largest distance from the vertices and edge midpoints of `p` to the boundary of `q`.
double one_sided(const std::vector<PdfPoint>& p, const std::vector<PdfPoint>& q) {
    double worst = 0;
    auto to_q = [&](const PdfPoint& x) {
        double best = std::numeric_limits<double>::infinity();
        if (q.size() == 1) return std::hypot(x.x - q[0].x, x.y - q[0].y);
        for (std::size_t k = 0; k < q.size(); ++k)
            best = std::min(best, seg_distance(x, q[k], q[(k + 1) % q.size()]));
        return best;
    };
    for (std::size_t k = 0; k < p.size(); ++k) {
        const PdfPoint& a = p[k];
        const PdfPoint& b = p[(k + 1) % p.size()];
        worst = std::max({worst, to_q(a), to_q({0.5 * (a.x + b.x), 0.5 * (a.y + b.y)})});
    }
    return worst;
}

}  // namespace

PdfPage read_pdf_page(std::string_view pdf) {
    if (pdf.substr(0, 5) != "%PDF-") throw bad("no %PDF- header: not a PDF file");
    PdfPage page;
    const std::string content = page_content(pdf, page);
    std::vector<double> operands;
    std::vector<Matrix> stack;
    Matrix ctm;
    double colour[3] = {0, 0, 0};
    std::vector<std::vector<PdfPoint>> path;
    bool open = false;  // the last subpath is still open (after m/l)
    std::size_t i = 0;
    auto need = [&](const std::string& op, std::size_t n) {
        if (operands.size() != n)
            throw bad("operator " + op + " with " + std::to_string(operands.size()) +
                      " operands (expected " + std::to_string(n) + ")");
    };
    while (i < content.size()) {
        const char c = content[i];
        if (std::isspace(static_cast<unsigned char>(c))) {
            ++i;
            continue;
        }
        if (c == '%') {  // comment to end of line
            while (i < content.size() && content[i] != '\n' && content[i] != '\r') ++i;
            continue;
        }
        if (c == '/') {  // a name operand (only gs takes one)
            ++i;
            while (i < content.size() && !is_delimiter(content[i])) ++i;
            operands.push_back(std::numeric_limits<double>::quiet_NaN());
            continue;
        }
        if (std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.') {
            const char* start = content.c_str() + i;
            char* end = nullptr;
            const double v = std::strtod(start, &end);
            if (end == start || !std::isfinite(v))
                throw bad("malformed number in the content stream at byte " + std::to_string(i));
            i += std::size_t(end - start);
            if (operands.size() >= kMaxOperands) throw bad("too many operands");
            operands.push_back(v);
            continue;
        }
        std::size_t j = i;
        while (j < content.size() && !is_delimiter(content[j])) ++j;
        if (j == i) throw bad(std::string("unsupported token '") + c + "' in the content stream");
        const std::string op = content.substr(i, j - i);
        i = j;
        if (op == "q") {
            stack.push_back(ctm);
        } else if (op == "Q") {
            if (stack.empty()) throw bad("Q without q");
            ctm = stack.back();
            stack.pop_back();
        } else if (op == "cm") {
            need(op, 6);
            ctm = ctm.after(
                {operands[0], operands[1], operands[2], operands[3], operands[4], operands[5]});
        } else if (op == "rg") {
            need(op, 3);
            std::copy(operands.begin(), operands.end(), colour);
        } else if (op == "g") {
            need(op, 1);
            colour[0] = colour[1] = colour[2] = operands[0];
        } else if (op == "RG" || op == "G" || op == "w" || op == "gs") {
            // stroke colour, line width, alpha state: no effect on fills
        } else if (op == "m") {
            need(op, 2);
            if (open && path.back().size() == 1) path.pop_back();  // a lone move-to
            path.push_back({ctm.apply(operands[0], operands[1])});
            open = true;
        } else if (op == "l") {
            need(op, 2);
            if (!open) throw bad("l without a current point");
            path.back().push_back(ctm.apply(operands[0], operands[1]));
        } else if (op == "h") {
            if (path.empty()) throw bad("h without a path");
            open = false;
        } else if (op == "re") {
            need(op, 4);
            const double x = operands[0], y = operands[1], w = operands[2], h = operands[3];
            if (open && path.back().size() == 1) path.pop_back();
            path.push_back({ctm.apply(x, y), ctm.apply(x + w, y), ctm.apply(x + w, y + h),
                            ctm.apply(x, y + h)});
            open = false;
        } else if (op == "f" || op == "f*" || op == "F") {
            if (open && !path.empty() && path.back().size() == 1) path.pop_back();
            PdfPathFill fill{colour[0], colour[1], colour[2], std::move(path)};
            page.fills.push_back(std::move(fill));
            path.clear();
            open = false;
        } else if (op == "n") {
            path.clear();
            open = false;
        } else {
            throw bad("content operator '" + op.substr(0, 12) +
                      "' is not supported (pinmask reads filled paths: q Q cm rg g m l h re f)");
        }
        operands.clear();
    }
    if (!stack.empty()) throw bad("q without Q");
    return page;
}

bool PdfComparison::ok() const {
    return std::fabs(width_pt - expected_width_pt) <= kPageSizeTolerancePt &&
           std::fabs(height_pt - expected_height_pt) <= kPageSizeTolerancePt &&
           fills == expected_fills && colour_mismatches == 0 && ring_count_mismatches == 0 &&
           beyond_tolerance == 0;
}

std::string PdfComparison::describe() const {
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "page %.3f x %.3f pt (design %.3f x %.3f); %zu fills (design %zu), %zu rings "
                  "(design %zu); %zu colour and %zu ring-count mismatches; %zu rings beyond "
                  "%.0f nm, largest deviation %.0f nm",
                  width_pt, height_pt, expected_width_pt, expected_height_pt, fills, expected_fills,
                  rings, expected_rings, colour_mismatches, ring_count_mismatches, beyond_tolerance,
                  kPdfToleranceNm, max_deviation_nm);
    return buf;
}

PdfComparison compare_pdf(const PdfPage& page, const Layout& design, const PdfOptions& options) {
    const PdfDrawing want = pdf_drawing(design, options);
    PdfComparison c;
    c.width_pt = page.width_pt;
    c.height_pt = page.height_pt;
    c.expected_width_pt = want.width_pt;
    c.expected_height_pt = want.height_pt;
    // Cairo's white page paint: a white rectangle covering the page, first.
    std::size_t first = 0;
    if (!page.fills.empty() && page.fills[0].r == 1 && page.fills[0].g == 1 &&
        page.fills[0].b == 1 && page.fills[0].subpaths.size() == 1) {
        const auto& s = page.fills[0].subpaths[0];
        double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
        for (const PdfPoint& p : s) {
            x0 = std::min(x0, p.x), y0 = std::min(y0, p.y);
            x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
        }
        if (s.size() == 4 && x0 <= 0 && y0 <= 0 && x1 >= page.width_pt - kPageSizeTolerancePt &&
            y1 >= page.height_pt - kPageSizeTolerancePt)
            first = 1;
    }
    c.fills = page.fills.size() - first;
    c.expected_fills = want.fills.size();
    const double k = kPdfPointsPerNm, tol_pt = kPdfToleranceNm * k;
    const double ox = double(want.margin_nm - want.page_nm.x0);
    const double oy = double(want.margin_nm - want.page_nm.y0);
    for (std::size_t f = 0; f < std::min(c.fills, c.expected_fills); ++f) {
        const PdfPathFill& got = page.fills[first + f];
        const PdfFill& exp = want.fills[f];
        const double v = exp.white ? 1.0 : 0.0;
        if (got.r != v || got.g != v || got.b != v) ++c.colour_mismatches;
        c.rings += got.subpaths.size();
        c.expected_rings += exp.rings.size();
        if (got.subpaths.size() != exp.rings.size()) {
            ++c.ring_count_mismatches;
            continue;
        }
        std::vector<PdfPoint> ring;
        for (std::size_t r = 0; r < exp.rings.size(); ++r) {
            ring.clear();
            for (const PointNm& p : exp.rings[r])
                ring.push_back({(double(p.x) + ox) * k, (double(p.y) + oy) * k});
            const auto& s = got.subpaths[r];
            // Same vertices in the same order (Cairo keeps the order): the boundaries are then
            // within the largest vertex distance of each other everywhere. Else (a rectangle
            // written as re, vertices merged by the fixed point) vertex-to-boundary distances.
            double d = std::numeric_limits<double>::infinity();
            if (s.size() == ring.size()) {
                d = 0;
                for (std::size_t v = 0; v < s.size(); ++v)
                    d = std::max(d, std::hypot(s[v].x - ring[v].x, s[v].y - ring[v].y));
            }
            if (!(d <= tol_pt)) d = std::max(one_sided(s, ring), one_sided(ring, s));
            c.max_deviation_nm = std::max(c.max_deviation_nm, d / k);
            if (!(d <= tol_pt)) ++c.beyond_tolerance;
        }
    }
    return c;
}

}  // namespace pinmask
