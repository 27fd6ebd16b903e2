#include "export/dxf_reader.hpp"

#include <charconv>
#include <optional>
#include <string>

#include "core/error.hpp"
#include "export/decimal.hpp"
#include "export/geometry.hpp"

namespace pinmask {
namespace {

constexpr int kMicrometreDigits = 3;

struct Pair {
    int code = 0;
    std::string_view value;
    std::size_t line = 0;  // 1-based line of the group code
};

InvalidInput bad(std::size_t line, const std::string& rule) {
    return InvalidInput("dxf: line " + std::to_string(line) + ": " + rule);
}

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
        s.remove_suffix(1);
    return s;
}

class PairReader {
  public:
    explicit PairReader(std::string_view t) : t_(t) {}

    bool at_end() const { return pos_ >= t_.size(); }

    Pair next() {
        Pair p;
        p.line = line_ + 1;
        const std::string_view code = trim(read_line());
        const auto [ptr, ec] = std::from_chars(code.data(), code.data() + code.size(), p.code);
        if (ec != std::errc() || ptr != code.data() + code.size() || code.empty())
            throw bad(p.line,
                      "group code '" + std::string(code.substr(0, 20)) + "' is not an integer");
        if (at_end()) throw bad(p.line, "group code without a value: truncated");
        p.value = trim(read_line());
        return p;
    }

    // Puts the pair back so the next next() returns it again.
    void unread(const Pair& p) { saved_ = p; }
    Pair take() {
        if (saved_) {
            Pair p = *saved_;
            saved_.reset();
            return p;
        }
        if (at_end()) throw bad(line_ + 1, "file ends without EOF: truncated");
        return next();
    }

  private:
    std::string_view read_line() {
        const std::size_t nl = t_.find('\n', pos_);
        const std::size_t end = nl == std::string_view::npos ? t_.size() : nl;
        const std::string_view l = t_.substr(pos_, end - pos_);
        pos_ = end + 1;
        ++line_;
        return l;
    }

    std::string_view t_;
    std::size_t pos_ = 0;
    std::size_t line_ = 0;
    std::optional<Pair> saved_;
};

std::int64_t coordinate(const Pair& p) {
    try {
        return parse_scaled(p.value, kMicrometreDigits, "dxf coordinate");
    } catch (const InvalidInput& e) {
        throw bad(p.line, e.what());
    }
}

int integer(const Pair& p) {
    int v = 0;
    const auto [ptr, ec] = std::from_chars(p.value.data(), p.value.data() + p.value.size(), v);
    if (ec != std::errc() || ptr != p.value.data() + p.value.size())
        throw bad(p.line, "value '" + std::string(p.value.substr(0, 20)) + "' is not an integer");
    return v;
}

void check_bulge(const Pair& p) {
    for (char c : p.value)
        if (c >= '1' && c <= '9') throw bad(p.line, "arc segments (bulge) are not supported");
}

void finish(Ring ring, bool closed, std::size_t line, std::vector<Ring>& out) {
    if (ring.size() >= 2 && ring.front() == ring.back()) {
        ring.pop_back();
        closed = true;
    }
    if (!closed) throw bad(line, "polyline is not closed");
    if (ring.size() < 3) throw bad(line, "polyline has fewer than 3 vertices");
    out.push_back(std::move(ring));
}

// A POLYLINE entity: its own groups, then VERTEX entities, then SEQEND.
void read_polyline(PairReader& rd, std::size_t line, std::vector<Ring>& out) {
    bool closed = false;
    Pair p;
    while ((p = rd.take()).code != 0) {
        if (p.code == 70) {
            const int flags = integer(p);
            if (flags & ~(1 | 128)) throw bad(p.line, "only plain 2D polylines are supported");
            closed = flags & 1;
        }
    }
    Ring ring;
    while (p.value == "VERTEX") {
        PointNm v;
        bool has_x = false, has_y = false;
        while ((p = rd.take()).code != 0) {
            if (p.code == 10) v.x = coordinate(p), has_x = true;
            if (p.code == 20) v.y = coordinate(p), has_y = true;
            if (p.code == 42) check_bulge(p);
        }
        if (!has_x || !has_y) throw bad(line, "VERTEX without 10/20 coordinates");
        ring.push_back(v);
    }
    if (p.value != "SEQEND") throw bad(p.line, "POLYLINE not ended by SEQEND");
    while ((p = rd.take()).code != 0) {
    }
    rd.unread(p);
    finish(std::move(ring), closed, line, out);
}

void read_lwpolyline(PairReader& rd, std::size_t line, std::vector<Ring>& out) {
    bool closed = false;
    Ring ring;
    Pair p;
    while ((p = rd.take()).code != 0) {
        if (p.code == 70) closed = integer(p) & 1;
        if (p.code == 10) ring.push_back({coordinate(p), 0});
        if (p.code == 20) {
            if (ring.empty()) throw bad(p.line, "20 before 10");
            ring.back().y = coordinate(p);
        }
        if (p.code == 42) check_bulge(p);
    }
    rd.unread(p);
    finish(std::move(ring), closed, line, out);
}

}  // namespace

FileGeometry read_dxf(std::string_view text) {
    FileGeometry g;
    PairReader rd(text);
    std::string section;
    for (;;) {
        const Pair p = rd.take();
        if (p.code == 999) {
            for (const auto& [k, v] : parse_info(p.value)) g.info[k] = v;
            continue;
        }
        if (p.code != 0) {
            if (section.empty()) throw bad(p.line, "group outside a section");
            continue;
        }
        if (p.value == "EOF") break;
        if (p.value == "SECTION") {
            const Pair name = rd.take();
            if (name.code != 2) throw bad(name.line, "SECTION without a name");
            section = std::string(name.value);
            continue;
        }
        if (p.value == "ENDSEC") {
            section.clear();
            continue;
        }
        if (section != "ENTITIES") continue;
        if (p.value == "POLYLINE")
            read_polyline(rd, p.line, g.rings);
        else if (p.value == "LWPOLYLINE")
            read_lwpolyline(rd, p.line, g.rings);
        else
            throw bad(p.line, "unsupported entity " + std::string(p.value.substr(0, 20)) +
                                  " (pinmask reads closed POLYLINE and LWPOLYLINE only)");
    }
    return g;
}

}  // namespace pinmask
