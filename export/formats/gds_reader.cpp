#include "export/formats/gds_reader.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/errors/error.hpp"
#include "core/limits/resource_limits.hpp"
#include "export/formats/gds_writer.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/xor_area.hpp"

namespace pinmask {
namespace {

InvalidInput bad(std::size_t offset, const std::string& rule) {
    return InvalidInput("gds: at byte " + std::to_string(offset) + ": " + rule);
}

struct Record {
    std::uint8_t type = 0;
    std::uint8_t data_type = 0;
    std::string_view data;
    std::size_t offset = 0;
};

class RecordReader {
  public:
    explicit RecordReader(std::string_view bytes) : b_(bytes) {}

    bool at_end() const { return pos_ >= b_.size(); }
    std::size_t offset() const { return pos_; }

    Record next() {
        if (b_.size() - pos_ < 4) throw bad(pos_, "truncated record header");
        const auto u8 = [&](std::size_t i) { return static_cast<std::uint8_t>(b_[pos_ + i]); };
        const std::size_t len = std::size_t(u8(0)) << 8 | u8(1);
        if (len < 4 || len % 2)
            throw bad(pos_, "record length " + std::to_string(len) + " is not an even number >= 4");
        if (len > b_.size() - pos_)
            throw bad(pos_, "record of " + std::to_string(len) + " bytes runs past the end (" +
                                std::to_string(b_.size() - pos_) + " left): truncated");
        Record r{u8(2), u8(3), b_.substr(pos_ + 4, len - 4), pos_};
        pos_ += len;
        return r;
    }

    // Only zero bytes may follow ENDLIB (block padding).
    void expect_padding() const {
        for (std::size_t i = pos_; i < b_.size(); ++i)
            if (b_[i] != '\0') throw bad(i, "data after ENDLIB");
    }

  private:
    std::string_view b_;
    std::size_t pos_ = 0;
};

std::int64_t be(std::string_view d, std::size_t at, int bytes) {
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v = (v << 8) | static_cast<std::uint8_t>(d[at + i]);
    if (bytes == 2) return static_cast<std::int16_t>(v);
    if (bytes == 4) return static_cast<std::int32_t>(v);
    return static_cast<std::int64_t>(v);
}

void expect(const Record& r, std::uint8_t data_type, std::size_t unit, const char* name) {
    if (r.data_type != data_type || (unit && r.data.size() % unit) || (unit && r.data.empty()))
        throw bad(r.offset, std::string("malformed ") + name + " record");
}

std::string ascii(const Record& r) {
    std::string s(r.data);
    while (!s.empty() && s.back() == '\0') s.pop_back();
    return s;
}

constexpr int kMaxStructures = 100000;
constexpr int kMaxDepth = 16;

struct Reference {
    std::string name;
    bool array = false;
    std::int64_t cols = 1, rows = 1;
    PointNm xy[3];
};

struct Structure {
    std::vector<Ring> rings;
    std::vector<Reference> refs;
    double check_bytes = 0.0;  // its rings' cost through the check (ring_check_bytes)
};

// Appends the rings of `name` translated by `at`, references expanded (translation only).
// Placements visited at most while flattening (bounds the time of nested arrays of empty cells).
constexpr std::uint64_t kMaxPlacements = 100'000'000;

// `bytes`: what the rings placed so far cost through the check, charged against the memory
// budget as they are placed (references multiply a small file into millions of rings).
void flatten(const std::map<std::string, Structure>& all, const std::string& name, PointNm at,
             int depth, std::vector<Ring>& out, std::uint64_t& visits, double& bytes) {
    if (depth > kMaxDepth)
        throw bad(0, "references nested deeper than " + std::to_string(kMaxDepth));
    if (++visits > kMaxPlacements) throw bad(0, "references expand to more than 10^8 placements");
    const Structure& s = all.at(name);
    bytes += s.check_bytes;
    check_memory(bytes, "GDSII flattening (references expanded)");
    for (const Ring& r : s.rings) {
        Ring t = r;
        for (PointNm& p : t) {
            p = {p.x + at.x, p.y + at.y};
            if (std::llabs(p.x) > kMaxCoordNm || std::llabs(p.y) > kMaxCoordNm)
                throw bad(0, "flattened coordinate beyond 2^30 nm");
        }
        out.push_back(std::move(t));
    }
    for (const Reference& ref : s.refs) {
        if (!ref.array) {
            flatten(all, ref.name, {at.x + ref.xy[0].x, at.y + ref.xy[0].y}, depth + 1, out, visits,
                    bytes);
            continue;
        }
        // AREF: xy[1] = origin + cols * column step, xy[2] = origin + rows * row step.
        const PointNm o = ref.xy[0];
        const PointNm c{ref.xy[1].x - o.x, ref.xy[1].y - o.y},
            r{ref.xy[2].x - o.x, ref.xy[2].y - o.y};
        if (c.x % ref.cols || c.y % ref.cols || r.x % ref.rows || r.y % ref.rows)
            throw bad(0, "AREF steps are not whole database units");
        for (std::int64_t j = 0; j < ref.rows; ++j)
            for (std::int64_t i = 0; i < ref.cols; ++i)
                flatten(all, ref.name,
                        {at.x + o.x + i * (c.x / ref.cols) + j * (r.x / ref.rows),
                         at.y + o.y + i * (c.y / ref.cols) + j * (r.y / ref.rows)},
                        depth + 1, out, visits, bytes);
    }
}

}  // namespace

FileGeometry read_gds(std::string_view bytes) {
    enum Type : std::uint8_t {
        HEADER = 0x00,
        BGNLIB = 0x01,
        LIBNAME = 0x02,
        UNITS = 0x03,
        ENDLIB = 0x04,
        BGNSTR = 0x05,
        STRNAME = 0x06,
        ENDSTR = 0x07,
        BOUNDARY = 0x08,
        PATH = 0x09,
        SREF = 0x0A,
        AREF = 0x0B,
        TEXT = 0x0C,
        LAYER = 0x0D,
        DATATYPE = 0x0E,
        XY = 0x10,
        ENDEL = 0x11,
        NODE = 0x15,
        TEXTTYPE = 0x16,
        STRING = 0x19,
        BOX = 0x2D,
        SNAME = 0x12,
        COLROW = 0x13,
        STRANS = 0x1A,
        MAG = 0x1B,
        ANGLE = 0x1C,
    };
    FileGeometry g;
    std::map<std::string, Structure> structures_by_name;
    std::vector<std::string> order;  // structure names in file order
    Structure* current = nullptr;
    RecordReader rd(bytes);
    Record r = rd.next();
    if (r.type != HEADER) throw bad(0, "not a GDSII stream (no HEADER record)");
    // Stream versions in use: 0 and 3..7 (Calma releases) and 600..799 (6.0, 7.0 as written by
    // KLayout, Virtuoso and pinmask). Anything else is a damaged or foreign file.
    expect(r, 2, 2, "HEADER");
    if (const std::int64_t v = be(r.data, 0, 2);
        !(v == 0 || (v >= 3 && v <= 7) || (v >= 600 && v < 800)))
        throw bad(r.offset, "unknown GDSII stream version " + std::to_string(v) +
                                " in HEADER (expected 0, 3..7 or 600..799)");
    std::int64_t scale_nm = 0;  // nanometres per database unit
    int structures = 0;
    bool in_structure = false, ended = false;
    std::string layers;
    std::set<std::string> layer_seen;  // the layers of `layers`
    TimeLimitPoll poll_time("reading the GDSII file");
    while (!ended) {
        poll_time();
        if (rd.at_end()) throw bad(rd.offset(), "stream ends before ENDLIB: truncated");
        r = rd.next();
        switch (r.type) {
            case LIBNAME:
                g.info["library"] = ascii(r);
                break;
            case UNITS: {
                expect(r, 5, 16, "UNITS");
                const double db_m = gds_real8_value(std::uint64_t(be(r.data, 8, 8)));
                const double nm = db_m * 1e9;
                const std::int64_t k = std::llround(nm);
                if (!(k >= 1 && k <= 1'000'000) || std::fabs(nm - double(k)) > 1e-6 * double(k))
                    throw bad(r.offset, "database unit " + std::to_string(db_m) +
                                            " m is not a whole number of nanometres in 1 nm..1 mm");
                scale_nm = k;
                char buf[32];
                std::snprintf(buf, sizeof buf, "%.6g", db_m);
                g.info["db_unit_m"] = buf;
                break;
            }
            case BGNSTR:
                if (in_structure) throw bad(r.offset, "BGNSTR inside a structure");
                if (++structures > kMaxStructures)
                    throw bad(r.offset,
                              "more than " + std::to_string(kMaxStructures) + " structures");
                in_structure = true;
                current = nullptr;
                break;
            case STRNAME: {
                if (!in_structure || current) throw bad(r.offset, "STRNAME out of place");
                const std::string name = ascii(r);
                if (structures_by_name.count(name))
                    throw bad(r.offset, "structure " + name + " defined twice");
                current = &structures_by_name[name];
                order.push_back(name);
                break;
            }
            case ENDSTR:
                if (!in_structure) throw bad(r.offset, "ENDSTR outside a structure");
                in_structure = false;
                break;
            case ENDLIB:
                if (in_structure) throw bad(r.offset, "ENDLIB inside a structure");
                ended = true;
                break;
            case SREF:
            case AREF: {
                if (!in_structure || !current) throw bad(r.offset, "element outside a structure");
                if (scale_nm == 0) throw bad(r.offset, "element before the UNITS record");
                Reference ref;
                ref.array = r.type == AREF;
                bool have_xy = false, have_colrow = false;
                for (;;) {
                    if (rd.at_end()) throw bad(rd.offset(), "element not ended: truncated");
                    const Record e = rd.next();
                    if (e.type == ENDEL) break;
                    if (e.type == SNAME) {
                        ref.name = ascii(e);
                    } else if (e.type == STRANS) {
                        expect(e, 1, 2, "STRANS");
                        if (be(e.data, 0, 2) != 0)
                            throw bad(e.offset,
                                      "reference with reflection, absolute "
                                      "magnification or angle (STRANS) is not supported");
                    } else if (e.type == MAG || e.type == ANGLE) {
                        expect(e, 5, 8, "MAG/ANGLE");
                        const double v = gds_real8_value(std::uint64_t(be(e.data, 0, 8)));
                        if (v != (e.type == MAG ? 1.0 : 0.0))
                            throw bad(e.offset, std::string("reference with ") +
                                                    (e.type == MAG ? "magnification" : "rotation") +
                                                    " is not supported");
                    } else if (e.type == COLROW) {
                        expect(e, 2, 4, "COLROW");
                        ref.cols = be(e.data, 0, 2);
                        ref.rows = be(e.data, 2, 2);
                        if (ref.cols < 1 || ref.rows < 1)
                            throw bad(e.offset, "COLROW must be >= 1 x 1");
                        have_colrow = true;
                    } else if (e.type == XY) {
                        expect(e, 3, 8, "XY");
                        if (have_xy) throw bad(e.offset, "second XY record in one element");
                        have_xy = true;
                        const std::size_t n = e.data.size() / 8;
                        if (n != (ref.array ? 3u : 1u))
                            throw bad(e.offset, ref.array ? "AREF needs 3 XY points"
                                                          : "SREF needs 1 XY point");
                        for (std::size_t i = 0; i < n; ++i)
                            ref.xy[i] = {be(e.data, 8 * i, 4) * scale_nm,
                                         be(e.data, 8 * i + 4, 4) * scale_nm};
                    } else if (e.type == BGNSTR || e.type == ENDSTR || e.type == ENDLIB ||
                               e.type == BOUNDARY || e.type == TEXT || e.type == SREF ||
                               e.type == AREF) {
                        throw bad(e.offset, "element not ended with ENDEL");
                    }
                }
                if (!have_xy || ref.name.empty()) throw bad(r.offset, "reference without SNAME/XY");
                if (ref.array && !have_colrow) throw bad(r.offset, "AREF without COLROW");
                current->refs.push_back(std::move(ref));
                break;
            }
            case BOUNDARY:
            case TEXT: {
                if (!in_structure || !current) throw bad(r.offset, "element outside a structure");
                if (scale_nm == 0) throw bad(r.offset, "element before the UNITS record");
                const bool boundary = r.type == BOUNDARY;
                Ring ring;
                std::string layer_text;
                // What identifies the film: one LAYER and one DATATYPE per BOUNDARY, each in
                // 0..32767 (a second record, or none, leaves the layer to the reading tool).
                int layer = -1, datatype = -1;
                bool have_xy = false;
                for (;;) {
                    if (rd.at_end()) throw bad(rd.offset(), "element not ended: truncated");
                    const Record e = rd.next();
                    if (e.type == ENDEL) break;
                    if (e.type == LAYER || e.type == DATATYPE || e.type == TEXTTYPE) {
                        expect(e, 2, 2, "LAYER/DATATYPE");
                        if (e.type != TEXTTYPE) {
                            const char* what = e.type == LAYER ? "LAYER" : "DATATYPE";
                            int& v = e.type == LAYER ? layer : datatype;
                            if (v >= 0)
                                throw bad(e.offset,
                                          std::string("second ") + what + " record in one element");
                            v = int(be(e.data, 0, 2));
                            if (v < 0)
                                throw bad(e.offset, std::string(what) + " " + std::to_string(v) +
                                                        " is negative (0..32767)");
                        }
                    } else if (e.type == XY) {
                        expect(e, 3, 8, "XY");
                        if (have_xy) throw bad(e.offset, "second XY record in one element");
                        have_xy = true;
                        const std::size_t n = e.data.size() / 8;
                        ring.reserve(n);
                        for (std::size_t i = 0; i < n; ++i)
                            ring.push_back({be(e.data, 8 * i, 4) * scale_nm,
                                            be(e.data, 8 * i + 4, 4) * scale_nm});
                    } else if (e.type == STRING) {
                        if (boundary) throw bad(e.offset, "STRING in a BOUNDARY");
                        for (const auto& [k, v] : parse_info(ascii(e))) g.info[k] = v;
                    } else if (e.type == BGNSTR || e.type == ENDSTR || e.type == ENDLIB ||
                               e.type == BOUNDARY || e.type == TEXT) {
                        throw bad(e.offset, "element not ended with ENDEL");
                    }
                    // Other element records (PROPATTR, PRESENTATION, STRANS, ...) are ignored.
                }
                if (!have_xy) throw bad(r.offset, "element without XY");
                if (boundary && (layer < 0 || datatype < 0))
                    throw bad(r.offset, std::string("BOUNDARY without a ") +
                                            (layer < 0 ? "LAYER" : "DATATYPE") +
                                            " record: its layer is the reading tool's guess");
                if (boundary) layer_text = std::to_string(layer) + "/" + std::to_string(datatype);
                if (boundary) {
                    if (ring.size() < 4 || !(ring.front() == ring.back()))
                        throw bad(r.offset,
                                  "BOUNDARY must have >= 4 points and end at its "
                                  "first point");
                    ring.pop_back();
                    current->check_bytes += ring_check_bytes(ring.size());
                    current->rings.push_back(std::move(ring));
                    if (layer_seen.insert(layer_text).second) {
                        layers += (layers.empty() ? "" : " ") + layer_text;
                        g.layers.push_back(layer_text);
                    }
                }
                break;
            }
            case PATH:
            case NODE:
            case BOX:
                throw bad(r.offset,
                          "unsupported element (pinmask reads BOUNDARY, TEXT, SREF and AREF only)");
            case ENDEL:
            case XY:
                throw bad(r.offset, "element record outside an element");
            default:
                break;  // BGNLIB, REFLIBS, FONTS, GENERATIONS, FORMAT ...: no geometry
        }
    }
    rd.expect_padding();
    if (structures == 0) throw bad(0, "no structure");
    g.info["layers"] = layers;
    // The top structure: the one no other references.
    std::map<std::string, int> referenced;
    for (const auto& [name, st] : structures_by_name)
        for (const Reference& ref : st.refs) {
            if (!structures_by_name.count(ref.name))
                throw bad(0, "reference to undefined structure " + ref.name);
            referenced[ref.name]++;
        }
    std::string top;
    for (const std::string& name : order)
        if (!referenced.count(name)) {
            if (!top.empty())
                throw bad(0, "more than one top structure (" + top + ", " + name + ")");
            top = name;
        }
    if (top.empty()) throw bad(0, "no top structure (references form a cycle)");
    g.info["structure"] = top;
    if (order.size() > 1) g.info["hierarchy"] = "yes";
    std::uint64_t visits = 0;
    double charged = 0.0;  // the rings' cost through the check so far (flatten)
    flatten(structures_by_name, top, {0, 0}, 0, g.rings, visits, charged);
    return g;
}

}  // namespace pinmask
