#include "export/formats/gerber_reader.hpp"

#include <cctype>
#include <map>
#include <string>

#include "core/errors/error.hpp"
#include "core/limits/resource_limits.hpp"
#include "export/formats/decimal.hpp"
#include "export/layout/geometry.hpp"

namespace pinmask {
namespace {

InvalidInput bad(std::size_t offset, const std::string& rule) {
    return InvalidInput("gerber: at byte " + std::to_string(offset) + ": " + rule);
}

class GerberParser {
  public:
    explicit GerberParser(std::string_view t) : t_(t) {}

    FileGeometry run() {
        TimeLimitPoll poll_time("reading the Gerber file");
        while (!ended_) {
            poll_time();
            skip_space();
            if (pos_ >= t_.size()) throw bad(pos_, "file ends without M02: truncated");
            if (t_[pos_] == '%') {
                const std::size_t close = t_.find('%', pos_ + 1);
                if (close == std::string_view::npos) throw bad(pos_, "unterminated % block");
                std::string_view block = t_.substr(pos_ + 1, close - pos_ - 1);
                const std::size_t at = pos_;
                pos_ = close + 1;
                extended(block, at);
            } else {
                const std::size_t star = t_.find('*', pos_);
                if (star == std::string_view::npos) throw bad(pos_, "command without '*'");
                const std::string_view cmd = t_.substr(pos_, star - pos_);
                const std::size_t at = pos_;
                pos_ = star + 1;
                word(cmd, at);
            }
        }
        skip_space();
        if (pos_ != t_.size()) throw bad(pos_, "data after M02");
        return std::move(g_);
    }

  private:
    void skip_space() {
        while (pos_ < t_.size() && std::isspace(static_cast<unsigned char>(t_[pos_]))) ++pos_;
    }

    void extended(std::string_view block, std::size_t at) {
        // One or more commands, each ending with '*'.
        while (!block.empty()) {
            while (!block.empty() && std::isspace(static_cast<unsigned char>(block.front())))
                block.remove_prefix(1);
            if (block.empty()) break;
            const std::size_t star = block.find('*');
            if (star == std::string_view::npos) throw bad(at, "extended command without '*'");
            const std::string_view c = block.substr(0, star);
            block.remove_prefix(star + 1);
            if (c.starts_with("FS")) {
                format(c, at);
            } else if (c == "MOMM") {
                mm_ = true;
            } else if (c.starts_with("MO")) {
                throw bad(at, "units must be millimetres (%MOMM*%)");
            } else if (c.starts_with("AD")) {
                aperture(c, at);
            } else if (c == "LPD") {
            } else if (c.starts_with("TF")) {
                const std::string_view a = c.substr(2);
                if (a.starts_with(".FilePolarity,")) {
                    // One film, one polarity: a second statement leaves the plotter to choose.
                    const std::string p(a.substr(14));
                    if (const auto it = g_.info.find("polarity"); it != g_.info.end())
                        throw bad(at, "file polarity stated twice (" + it->second + ", then " +
                                          p.substr(0, 20) + ")");
                    if (p != "Positive" && p != "Negative")
                        throw bad(at, "file polarity '" + p.substr(0, 20) +
                                          "' is neither Positive nor Negative");
                    g_.info["polarity"] = p;
                }
            } else if (c.starts_with("TA") || c.starts_with("TO") || c.starts_with("TD")) {
            } else {
                throw bad(at, "unsupported extended command '" + std::string(c.substr(0, 20)) +
                                  "' (pinmask files use regions only)");
            }
        }
    }

    // %ADDnnC,<diameter>*%: a circular aperture without a hole (the only kind pinmask reads).
    void aperture(std::string_view c, std::size_t at) {
        std::size_t i = 2;
        if (i >= c.size() || c[i] != 'D') throw bad(at, "malformed aperture definition");
        ++i;
        const std::size_t num = i;
        while (i < c.size() && std::isdigit(static_cast<unsigned char>(c[i]))) ++i;
        const std::string code(c.substr(num, i - num));
        if (code.empty() || code.size() > 6 || std::stol(code) < 10)
            throw bad(at, "aperture number must be 10 or more");
        if (c.substr(i, 2) != "C,")
            throw bad(at, "unsupported aperture '" + std::string(c.substr(0, 20)) +
                              "' (pinmask reads plain circles %ADDnnC,d*% only)");
        const std::string_view d = c.substr(i + 2);
        if (d.find('X') != std::string_view::npos)
            throw bad(at, "circular aperture with a hole is not supported");
        if (!mm_) throw bad(at, "aperture before %MOMM*%");
        std::int64_t nm = 0;
        try {
            nm = parse_scaled(d, 6, "gerber aperture diameter");
        } catch (const InvalidInput& e) {
            throw bad(at, e.what());
        }
        if (nm <= 0) throw bad(at, "aperture diameter must be > 0");
        if (apertures_.count(code)) throw bad(at, "aperture D" + code + " defined twice");
        apertures_[code] = nm;
    }

    void format(std::string_view c, std::size_t at) {
        // FSLAXidYid with equal X and Y formats.
        if (c.size() != 10 || c.substr(0, 5) != "FSLAX" || c[7] != 'Y' ||
            c.substr(5, 2) != c.substr(8, 2) || !std::isdigit(static_cast<unsigned char>(c[5])) ||
            !std::isdigit(static_cast<unsigned char>(c[6])))
            throw bad(at, "format must be %FSLAXnmYnm*% (leading zeros omitted, absolute)");
        const int decimals = c[6] - '0';
        if (decimals > 6 || c[5] - '0' > 6)
            throw bad(at, "at most 6 integer and 6 decimal digits (1 nm resolution)");
        scale_ = 1;
        for (int d = decimals; d < 6; ++d) scale_ *= 10;
    }

    std::int64_t number(std::string_view& s, std::size_t at) {
        std::size_t i = 0;
        if (i < s.size() && (s[i] == '-' || s[i] == '+')) ++i;
        const std::size_t digits_start = i;
        std::int64_t v = 0;
        while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) {
            if (i - digits_start >= 13) throw bad(at, "coordinate has too many digits");
            v = v * 10 + (s[i] - '0');
            ++i;
        }
        if (i == digits_start) throw bad(at, "expected a coordinate");
        const bool negative = s[0] == '-';
        s.remove_prefix(i);
        return (negative ? -v : v) * scale_;
    }

    void word(std::string_view c, std::size_t at) {
        if (c.starts_with("G04")) {
            for (const auto& [k, v] : parse_info(c.substr(3))) g_.info[k] = v;
            return;
        }
        if (c == "M02") {
            if (in_region_) throw bad(at, "M02 inside a region");
            ended_ = true;
            return;
        }
        if (c == "G36") {
            if (in_region_) throw bad(at, "G36 inside a region");
            in_region_ = true;
            return;
        }
        if (c == "G37") {
            if (!in_region_) throw bad(at, "G37 without G36");
            finish(at);
            in_region_ = false;
            return;
        }
        if (c.starts_with("G01")) c.remove_prefix(3);
        if (c.empty() || c == "G75") return;
        if (c.front() == 'D' && c.size() >= 3 && !(c == "D01" || c == "D02" || c == "D03")) {
            if (in_region_) throw bad(at, "aperture selection inside a region");
            const auto it = apertures_.find(std::string(c.substr(1)));
            if (it == apertures_.end())
                throw bad(at, "aperture " + std::string(c.substr(0, 20)) + " is not defined");
            aperture_nm_ = it->second;
            return;
        }
        if (c.front() != 'X' && c.front() != 'Y' && c.front() != 'D')
            throw bad(at, "unsupported command '" + std::string(c.substr(0, 20)) + "'");
        if (scale_ == 0 || !mm_) throw bad(at, "coordinates before %FS...*% and %MOMM*%");
        PointNm p = last_;
        if (c.front() == 'X') {
            c.remove_prefix(1);
            p.x = number(c, at);
        }
        if (!c.empty() && c.front() == 'Y') {
            c.remove_prefix(1);
            p.y = number(c, at);
        }
        if (c != "D01" && c != "D02" && c != "D03")
            throw bad(at, "operation must be D01, D02 or D03 (no arcs)");
        last_ = p;
        if (c == "D03") {
            if (in_region_) throw bad(at, "flash inside a region");
            if (aperture_nm_ <= 0) throw bad(at, "flash without a selected aperture");
            g_.circles.push_back({p, aperture_nm_});
            return;
        }
        if (c == "D02") {
            if (in_region_) finish(at);
            if (in_region_) contour_.push_back(p);
            return;
        }
        if (!in_region_) throw bad(at, "D01 outside a region (strokes are not supported)");
        if (contour_.empty()) throw bad(at, "D01 before the contour's D02");
        contour_.push_back(p);
    }

    void finish(std::size_t at) {
        if (contour_.empty()) return;
        if (contour_.size() < 4 || !(contour_.front() == contour_.back()))
            throw bad(at, "region contour is not closed or has fewer than 3 vertices");
        contour_.pop_back();
        g_.rings.push_back(std::move(contour_));
        contour_.clear();
    }

    std::string_view t_;
    std::size_t pos_ = 0;
    std::int64_t scale_ = 0;  // nm per coordinate unit
    bool mm_ = false;
    bool in_region_ = false;
    bool ended_ = false;
    PointNm last_;
    std::map<std::string, std::int64_t> apertures_;  // D code -> diameter nm
    std::int64_t aperture_nm_ = 0;                   // the selected aperture
    Ring contour_;
    FileGeometry g_;
};

}  // namespace

FileGeometry read_gerber(std::string_view text) {
    FileGeometry g = GerberParser(text).run();
    // A fabrication file that draws nothing cannot be a mask (gerbv shows an empty image): an
    // error, not a clean check of zero polygons.
    if (g.rings.empty() && g.circles.empty())
        throw bad(text.size(), "the file draws nothing (no region and no flash)");
    return g;
}

}  // namespace pinmask
