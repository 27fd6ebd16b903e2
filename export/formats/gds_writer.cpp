#include "export/formats/gds_writer.hpp"

#include <cmath>
#include <limits>
#include <string_view>

#include "core/errors/error.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/repetition.hpp"
#include "export/layout/window_cells.hpp"

namespace pinmask {
namespace {

// Record types (high byte) and data types (low byte) of the records we write.
enum : std::uint16_t {
    kHeader = 0x0002,
    kBgnLib = 0x0102,
    kLibName = 0x0206,
    kUnits = 0x0305,
    kEndLib = 0x0400,
    kBgnStr = 0x0502,
    kStrName = 0x0606,
    kEndStr = 0x0700,
    kBoundary = 0x0800,
    kSref = 0x0A00,
    kAref = 0x0B00,
    kSname = 0x1206,
    kColRow = 0x1302,
    kText = 0x0C00,
    kLayer = 0x0D02,
    kDataType = 0x0E02,
    kXy = 0x1003,
    kEndEl = 0x1100,
    kTextType = 0x1602,
    kString = 0x1906,
};

constexpr std::size_t kMaxXyPoints = 8191;  // (65535 - 4) / 8: the 16-bit record length

class Stream {
  public:
    void record(std::uint16_t type, std::size_t data_bytes) {
        u16(static_cast<std::uint16_t>(4 + data_bytes));
        u16(type);
    }
    void u16(std::uint16_t v) {
        out_.push_back(char(v >> 8));
        out_.push_back(char(v & 0xFF));
    }
    void i32(std::int32_t v) {
        const auto u = static_cast<std::uint32_t>(v);
        for (int s = 24; s >= 0; s -= 8) out_.push_back(char((u >> s) & 0xFF));
    }
    void u64(std::uint64_t v) {
        for (int s = 56; s >= 0; s -= 8) out_.push_back(char((v >> s) & 0xFF));
    }
    void i16_record(std::uint16_t type, std::int16_t v) {
        record(type, 2);
        u16(static_cast<std::uint16_t>(v));
    }
    void empty_record(std::uint16_t type) { record(type, 0); }
    void string_record(std::uint16_t type, std::string_view s) {
        const std::size_t n = s.size() + (s.size() % 2);  // padded to even length with NUL
        record(type, n);
        out_ += s;
        if (n != s.size()) out_.push_back('\0');
    }
    void timestamps(std::uint16_t type) {
        // Modification and access time, both 2000-01-01 00:00:00 (year as a full number).
        record(type, 24);
        for (int k = 0; k < 2; ++k)
            for (std::uint16_t v : {2000, 1, 1, 0, 0, 0}) u16(v);
    }
    void xy(const Ring& ring, bool close) {
        record(kXy, 8 * (ring.size() + (close ? 1 : 0)));
        for (const PointNm& p : ring) {
            i32(static_cast<std::int32_t>(p.x));
            i32(static_cast<std::int32_t>(p.y));
        }
        if (close) {
            i32(static_cast<std::int32_t>(ring.front().x));
            i32(static_cast<std::int32_t>(ring.front().y));
        }
    }
    std::string& bytes() { return out_; }

  private:
    std::string out_;
};

void check_ring(const Ring& r, std::size_t index) {
    if (r.size() < 3 || r.size() + 1 > kMaxXyPoints)
        throw invalid_field("polygon " + std::to_string(index),
                            std::to_string(r.size()) + " vertices",
                            "a GDSII boundary needs 3..8190 vertices");
    for (const PointNm& p : r)
        if (p.x < std::numeric_limits<std::int32_t>::min() ||
            p.x > std::numeric_limits<std::int32_t>::max() ||
            p.y < std::numeric_limits<std::int32_t>::min() ||
            p.y > std::numeric_limits<std::int32_t>::max())
            throw invalid_field("polygon " + std::to_string(index), "coordinate",
                                "outside the 32-bit GDSII range");
}

}  // namespace

std::uint64_t gds_real8_bits(double value) {
    if (!std::isfinite(value)) throw invalid_field("gds real", "non-finite", "must be finite");
    if (value == 0) return 0;
    const std::uint64_t sign = value < 0 ? (std::uint64_t{1} << 63) : 0;
    double m = std::fabs(value);
    int e = 64;
    while (m >= 1.0) {
        m /= 16.0;
        ++e;
    }
    while (m < 1.0 / 16.0) {
        m *= 16.0;
        --e;
    }
    // m in [1/16, 1): 56-bit mantissa, rounded to nearest (exact scaling by powers of two).
    std::uint64_t mant = static_cast<std::uint64_t>(std::llround(std::ldexp(m, 56)));
    if (mant >> 56) {  // rounding carried into a new hex digit
        mant >>= 4;
        ++e;
    }
    if (e > 127) throw invalid_field("gds real", std::to_string(value), "too large for GDSII");
    if (e < 0) return 0;
    return sign | (std::uint64_t(e) << 56) | mant;
}

double gds_real8_value(std::uint64_t bits) {
    const double sign = (bits >> 63) ? -1.0 : 1.0;
    const int e = int((bits >> 56) & 0x7F);
    const std::uint64_t mant = bits & ((std::uint64_t{1} << 56) - 1);
    return sign * std::ldexp(double(mant), 4 * (e - 64) - 56);
}

std::string gds_stream(const Layout& layout, const GdsOptions& o) {
    if (o.layer < 0 || o.layer > 32767)
        throw invalid_field("layer", std::to_string(o.layer), "must be in 0..32767");
    if (o.datatype < 0 || o.datatype > 32767)
        throw invalid_field("datatype", std::to_string(o.datatype), "must be in 0..32767");
    Stream s;
    std::size_t points = 0;
    for (const Ring& r : layout.polygons) points += r.size() + 1;
    s.bytes().reserve(256 + points * 8 + layout.polygons.size() * 28);
    s.i16_record(kHeader, 600);
    s.timestamps(kBgnLib);
    s.string_record(kLibName, "PINMASK");
    s.record(kUnits, 16);
    // user units per database unit: 1 nm / (nm per user unit)
    s.u64(gds_real8_bits(1.0 / double(nm_per_unit(o.unit))));
    s.u64(gds_real8_bits(1e-9));  // metres per database unit (1 nm)
    const std::string top = "PINMASK_" + layout.mask_hash;
    auto boundary = [&](const Ring& r) {
        s.empty_record(kBoundary);
        s.i16_record(kLayer, static_cast<std::int16_t>(o.layer));
        s.i16_record(kDataType, static_cast<std::int16_t>(o.datatype));
        s.xy(r, true);
        s.empty_record(kEndEl);
    };
    std::size_t index = 0;
    for (const auto* set : {&layout.polygons, &layout.annotations})
        for (const Ring& r : *set) check_ring(r, index++);
    Repetition rep;
    if (o.hierarchy) {
        rep = find_repetition(layout.polygons, layout.active_area, layout.tiles_rows,
                              layout.tiles_cols);
        if (rep.cols > 32767 || rep.rows > 32767) rep = find_repetition(layout.polygons, {}, 1, 1);
        auto sref = [&](const std::string& name, PointNm at) {
            s.empty_record(kSref);
            s.string_record(kSname, name);
            s.xy({at}, false);
            s.empty_record(kEndEl);
        };
        // Short cell names (they are repeated in every reference): "P" + 4 hex digits of the
        // mask hash + S<k> (a shape) or W<k> (a window of shapes, export/layout/window_cells).
        const std::string prefix = "P" + layout.mask_hash.substr(0, 4);
        const std::string shape_name = prefix + "S", window_name = prefix + "W";
        for (std::size_t k = 0; k < rep.shapes.size(); ++k) {
            s.timestamps(kBgnStr);
            s.string_record(kStrName, shape_name + std::to_string(k));
            boundary(rep.shapes[k]);
            s.empty_record(kEndStr);
        }
        const std::size_t name_bytes = (prefix.size() + 5 + 1) / 2 * 2;  // ~4 digits
        WindowCells windows = find_window_cells(
            rep.placements, {.ref_bytes = 24 + name_bytes, .cell_bytes = 28 + 4 + name_bytes + 4});
        // Stay within the structure count pinmask's reader accepts (export/formats/gds_reader).
        constexpr std::size_t kMaxWindowCells = 50'000;
        if (windows.cells.size() > kMaxWindowCells) windows = {};
        for (std::size_t k = 0; k < windows.cells.size(); ++k) {
            s.timestamps(kBgnStr);
            s.string_record(kStrName, window_name + std::to_string(k));
            for (const Placement& p : windows.cells[k])
                sref(shape_name + std::to_string(p.shape), p.at);
            s.empty_record(kEndStr);
        }
        s.timestamps(kBgnStr);
        s.string_record(kStrName, top + "_TILE");
        if (windows.w > 0) {
            for (const Placement& u : windows.uses)
                sref(window_name + std::to_string(u.shape), u.at);
        } else {
            for (const Placement& p : rep.placements)
                sref(shape_name + std::to_string(p.shape), p.at);
        }
        s.empty_record(kEndStr);
        s.timestamps(kBgnStr);
        s.string_record(kStrName, top);
        if (rep.cols * rep.rows > 1) {
            s.empty_record(kAref);
            s.string_record(kSname, top + "_TILE");
            s.record(kColRow, 4);
            s.u16(static_cast<std::uint16_t>(rep.cols));
            s.u16(static_cast<std::uint16_t>(rep.rows));
            s.xy({{0, 0}, {rep.cols * rep.pitch_x_nm, 0}, {0, rep.rows * rep.pitch_y_nm}}, false);
            s.empty_record(kEndEl);
        } else {
            sref(top + "_TILE", {0, 0});
        }
    } else {
        s.timestamps(kBgnStr);
        s.string_record(kStrName, top);
        for (const Ring& r : layout.polygons) boundary(r);
    }
    for (const Ring& r : layout.annotations) boundary(r);
    s.empty_record(kText);
    s.i16_record(kLayer, static_cast<std::int16_t>(o.layer));
    s.i16_record(kTextType, 0);
    s.xy({{layout.extent.x0, layout.extent.y0}}, false);
    s.string_record(kString,
                    "pinmask " + layout_info(layout, "nm") + " user_unit=" + fab_unit_name(o.unit));
    s.empty_record(kEndEl);
    s.empty_record(kEndStr);
    s.empty_record(kEndLib);
    return std::move(s.bytes());
}

}  // namespace pinmask
