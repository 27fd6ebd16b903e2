#include "export/formats/oasis_reader.hpp"

#include <cmath>
#include <optional>
#include <set>
#include <string>
#include <utility>

#include "core/errors/error.hpp"
#include "core/limits/resource_limits.hpp"
#include "export/formats/oasis_codec.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/xor_area.hpp"

namespace pinmask {
namespace {

using namespace oasis;

// Positions and repetition extents in database units stay below this (so sums of a position, a
// repetition offset and a point-list offset cannot overflow).
constexpr std::int64_t kMaxSpan = std::int64_t{1} << 40;
// Largest count of one repetition (a dimension of 2^24 already means 2^48 elements in a grid).
constexpr std::uint64_t kMaxRepetitionDimension = std::uint64_t{1} << 24;

InvalidInput bad(std::size_t at, const std::string& rule) {
    return InvalidInput("oasis: at byte " + std::to_string(at) + ": " + rule);
}

class OasisParser {
  public:
    explicit OasisParser(std::string_view b) : rd_(b) {}

    FileGeometry run() {
        if (rd_.at_end() || !std::string_view(bytes_of(kMagic.size())).starts_with(kMagic))
            throw bad(0, "not an OASIS file (no %SEMI-OASIS magic)");
        start();
        for (;;) {
            if (rd_.at_end()) throw bad(rd_.offset(), "file ends without END: truncated");
            const std::size_t at = rd_.offset();
            const std::uint64_t id = rd_.uint();
            switch (id) {
                case kPad:
                    break;
                case kEnd:
                    end(at);
                    return std::move(g_);
                case kCellNameImplicit:
                case kTextStringImplicit:
                    rd_.string();  // names for references; pinmask uses inline names
                    break;
                case kCellNameExplicit:
                case kTextStringExplicit:
                    rd_.string();
                    rd_.uint();
                    break;
                case kCellByName:
                    cell(at);
                    g_.info["cell"] = std::string(rd_.string());
                    break;
                case kCellByRef:
                    throw bad(at, "CELL by reference number is not supported (inline names only)");
                case kXyAbsolute:
                    relative_ = false;
                    break;
                case kXyRelative:
                    relative_ = true;
                    break;
                case kText:
                    text(at);
                    break;
                case kRectangle:
                    rectangle(at);
                    break;
                case kPolygon:
                    polygon(at);
                    break;
                default:
                    throw bad(at, "OASIS record " + record_name(id) + " (id " + std::to_string(id) +
                                      ") is not supported (pinmask reads one cell of RECTANGLE, "
                                      "POLYGON and TEXT records)");
            }
        }
    }

  private:
    std::string bytes_of(std::size_t n) {
        std::string s;
        for (std::size_t i = 0; i < n && !rd_.at_end(); ++i) s.push_back(char(rd_.byte()));
        return s;
    }

    void start() {
        const std::size_t at = rd_.offset();
        if (rd_.uint() != kStart) throw bad(at, "START record expected after the magic");
        const std::string_view version = rd_.string();
        if (version != "1.0")
            throw bad(at, "OASIS version '" + std::string(version) + "' is not 1.0");
        const double unit = rd_.real();  // grid steps per micron
        const double nm = 1000.0 / unit;
        const double k = std::round(nm);
        if (!std::isfinite(nm) || k < 1 || k > 1e6 || std::fabs(nm - k) > 1e-9 * k)
            throw bad(at, "database unit " + std::to_string(nm) +
                              " nm is not a whole number of nanometres in 1 nm..1 mm");
        scale_nm_ = std::int64_t(k);
        offset_flag_ = rd_.uint();
        if (offset_flag_ > 1) throw bad(at, "offset flag must be 0 or 1");
        if (offset_flag_ == 0)
            for (int i = 0; i < 12; ++i) rd_.uint();
    }

    void end(std::size_t at) {
        if (offset_flag_ == 1)
            for (int i = 0; i < 12; ++i) rd_.uint();
        rd_.string();  // padding
        const std::uint64_t scheme = rd_.uint();
        if (scheme == 1)
            rd_.skip(4);  // CRC32 (not verified)
        else if (scheme == 2)
            rd_.skip(4);  // checksum32 (not verified)
        else if (scheme != 0)
            throw bad(at, "unknown validation scheme " + std::to_string(scheme));
        if (!rd_.at_end()) throw bad(rd_.offset(), "data after the END record");
        if (cells_ == 0) throw bad(at, "no cell");
    }

    void cell(std::size_t at) {
        if (++cells_ > 1)
            throw bad(at, "more than one cell (pinmask files have one; hierarchy is not read)");
        // Modal variables are reset at each CELL.
        layer_.reset();
        datatype_.reset();
        w_.reset();
        h_.reset();
        points_.reset();
        x_ = y_ = 0;
        relative_ = false;
        repetition_.clear();
        have_repetition_ = false;
    }

    void need_cell(std::size_t at) const {
        if (cells_ == 0) throw bad(at, "element outside a cell");
    }

    std::int64_t coord(std::int64_t v, std::size_t at) const {
        if (v > kMaxCoordNm || v < -kMaxCoordNm) throw bad(at, "coordinate beyond 2^30 nm");
        const std::int64_t nm = v * scale_nm_;
        if (nm > kMaxCoordNm || nm < -kMaxCoordNm) throw bad(at, "coordinate beyond 2^30 nm");
        return nm;
    }

    void layer_fields(std::uint8_t info, std::size_t at) {
        if (info & kL) layer_ = rd_.uint();
        if (info & kD) datatype_ = rd_.uint();
        if (!layer_ || !datatype_) throw bad(at, "layer or datatype used before it is set");
        if (layer_seen_.insert({*layer_, *datatype_}).second)
            g_.layers.push_back(std::to_string(*layer_) + "/" + std::to_string(*datatype_));
    }

    void position(std::uint8_t info, std::size_t at) {
        if (info & kX) x_ = relative_ ? x_ + rd_.sint() : rd_.sint();
        if (info & kY) y_ = relative_ ? y_ + rd_.sint() : rd_.sint();
        if (std::llabs(x_) > kMaxSpan || std::llabs(y_) > kMaxSpan)
            throw bad(at, "position beyond 2^40 database units");
    }

    // A repetition's extent (count - 1 steps of `step`) must stay within 2^40 units.
    static void check_span(std::uint64_t n, std::int64_t step, std::size_t at) {
        if (double(n) * double(std::llabs(step)) > double(kMaxSpan))
            throw bad(at, "repetition extends beyond 2^40 database units");
    }

    // Offsets (database units) of a repetition; type 0 reuses the modal one.
    void repetition(std::size_t at) {
        const std::uint64_t type = rd_.uint();
        if (type == 0) {
            if (!have_repetition_) throw bad(at, "repetition type 0 without a previous one");
            return;
        }
        std::vector<PointNm> r;
        auto dim = [&](std::uint64_t extra) {
            const std::uint64_t d = rd_.uint();
            if (d > kMaxRepetitionDimension) throw bad(at, "repetition dimension too large");
            return d + extra;
        };
        auto reserve = [&](double n) {
            check_memory(n * (sizeof(PointNm) + 64.0), "OASIS repetition");
            r.reserve(std::size_t(n));
        };
        switch (type) {
            case 1: {
                const std::uint64_t nx = dim(2), ny = dim(2);
                const std::int64_t sx = std::int64_t(rd_.uint() & ((1ULL << 40) - 1));
                const std::int64_t sy = std::int64_t(rd_.uint() & ((1ULL << 40) - 1));
                check_span(nx, sx, at);
                check_span(ny, sy, at);
                reserve(double(nx) * double(ny));
                for (std::uint64_t j = 0; j < ny; ++j)
                    for (std::uint64_t i = 0; i < nx; ++i)
                        r.push_back({std::int64_t(i) * sx, std::int64_t(j) * sy});
                break;
            }
            case 2:
            case 3: {
                const std::uint64_t n = dim(2);
                const std::int64_t s = std::int64_t(rd_.uint() & ((1ULL << 40) - 1));
                check_span(n, s, at);
                reserve(double(n));
                for (std::uint64_t i = 0; i < n; ++i)
                    r.push_back(type == 2 ? PointNm{std::int64_t(i) * s, 0}
                                          : PointNm{0, std::int64_t(i) * s});
                break;
            }
            case 4:
            case 5:
            case 6:
            case 7: {
                const std::uint64_t n = dim(2);
                const std::int64_t grid =
                    (type == 5 || type == 7) ? std::int64_t(rd_.uint() & ((1ULL << 40) - 1)) : 1;
                reserve(double(n));
                std::int64_t p = 0;
                r.push_back({0, 0});
                for (std::uint64_t i = 1; i < n; ++i) {
                    const std::int64_t step = std::int64_t(rd_.uint() & ((1ULL << 40) - 1));
                    check_span(std::uint64_t(step), grid, at);
                    p += step * grid;
                    if (p > (1LL << 40)) throw bad(at, "repetition beyond 2^40");
                    r.push_back(type <= 5 ? PointNm{p, 0} : PointNm{0, p});
                }
                break;
            }
            case 8: {
                const std::uint64_t n = dim(2), m = dim(2);
                std::int64_t nx, ny, mx, my;
                rd_.gdelta(nx, ny);
                rd_.gdelta(mx, my);
                for (const std::int64_t v : {nx, ny}) check_span(n, v, at);
                for (const std::int64_t v : {mx, my}) check_span(m, v, at);
                reserve(double(n) * double(m));
                for (std::uint64_t j = 0; j < m; ++j)
                    for (std::uint64_t i = 0; i < n; ++i)
                        r.push_back({std::int64_t(i) * nx + std::int64_t(j) * mx,
                                     std::int64_t(i) * ny + std::int64_t(j) * my});
                break;
            }
            case 9: {
                const std::uint64_t n = dim(2);
                std::int64_t dx, dy;
                rd_.gdelta(dx, dy);
                check_span(n, dx, at);
                check_span(n, dy, at);
                reserve(double(n));
                for (std::uint64_t i = 0; i < n; ++i)
                    r.push_back({std::int64_t(i) * dx, std::int64_t(i) * dy});
                break;
            }
            case 10:
            case 11: {
                const std::uint64_t n = dim(2);
                const std::int64_t grid =
                    type == 11 ? std::int64_t(rd_.uint() & ((1ULL << 40) - 1)) : 1;
                reserve(double(n));
                PointNm p{0, 0};
                r.push_back(p);
                for (std::uint64_t i = 1; i < n; ++i) {
                    std::int64_t dx, dy;
                    rd_.gdelta(dx, dy);
                    check_span(std::uint64_t(std::llabs(dx)) + std::uint64_t(std::llabs(dy)), grid,
                               at);
                    p = {p.x + dx * grid, p.y + dy * grid};
                    if (std::llabs(p.x) > (1LL << 40) || std::llabs(p.y) > (1LL << 40))
                        throw bad(at, "repetition beyond 2^40");
                    r.push_back(p);
                }
                break;
            }
            default:
                throw bad(at, "unknown repetition type " + std::to_string(type));
        }
        repetition_ = std::move(r);
        have_repetition_ = true;
    }

    // Places `shape` (database units, relative to the element position) at every offset.
    void emit(const std::vector<PointNm>& shape, bool repeated, std::size_t at) {
        static const std::vector<PointNm> kOnce{{0, 0}};
        const std::vector<PointNm>& offsets = repeated ? repetition_ : kOnce;
        // Every ring made so far is charged, not only this record's: a repetition reused by
        // many records (type 0) multiplies a small file into millions of rings. Each at what
        // it costs through the whole check (export/layout/rings ring_check_bytes).
        expanded_bytes_ += double(offsets.size()) * ring_check_bytes(shape.size());
        check_memory(expanded_bytes_, "OASIS elements (repetitions expanded)");
        check_time_limit("reading the OASIS file (at byte " + std::to_string(at) + ")");
        for (const PointNm& o : offsets) {
            Ring ring;
            ring.reserve(shape.size());
            for (const PointNm& p : shape)
                ring.push_back({coord(x_ + o.x + p.x, at), coord(y_ + o.y + p.y, at)});
            g_.rings.push_back(std::move(ring));
        }
    }

    void rectangle(std::size_t at) {
        need_cell(at);
        const std::uint8_t info = rd_.byte();
        layer_fields(info, at);
        if (info & kW) w_ = rd_.uint();
        if (info & kH) {
            if (info & kS) throw bad(at, "RECTANGLE with both S and H bits");
            h_ = rd_.uint();
        }
        if (info & kS) h_ = w_;
        if (!w_ || !h_) throw bad(at, "RECTANGLE width or height used before it is set");
        position(info, at);
        if (info & kR) repetition(at);
        const auto w = std::int64_t(*w_ & ((1ULL << 40) - 1)),
                   h = std::int64_t(*h_ & ((1ULL << 40) - 1));
        emit({{0, 0}, {w, 0}, {w, h}, {0, h}}, info & kR, at);
    }

    void polygon(std::size_t at) {
        need_cell(at);
        const std::uint8_t info = rd_.byte();
        if (info & 0xC0) throw bad(at, "POLYGON info byte has reserved bits set");
        layer_fields(info, at);
        if (info & kP) points_ = point_list(at);
        if (!points_) throw bad(at, "POLYGON point list used before it is set");
        position(info, at);
        if (info & kR) repetition(at);
        emit(*points_, info & kR, at);
    }

    // A polygon's point list: the first vertex at the origin, then the deltas (types 0 and 1,
    // Manhattan, imply the closing edges).
    std::vector<PointNm> point_list(std::size_t at) {
        const std::uint64_t type = rd_.uint();
        const std::uint64_t n = rd_.uint();
        if (n > 8190) throw bad(at, "point list of " + std::to_string(n) + " deltas (max 8190)");
        std::vector<PointNm> pts{{0, 0}};
        PointNm p{0, 0};
        for (std::uint64_t i = 0; i < n; ++i) {
            std::int64_t dx = 0, dy = 0;
            switch (type) {
                case 0:
                case 1: {
                    const bool horizontal = (i % 2 == 0) == (type == 0);
                    (horizontal ? dx : dy) = rd_.sint();
                    break;
                }
                case 2: {  // 2-delta: (magnitude << 2) | direction (E N W S)
                    const std::uint64_t u = rd_.uint();
                    const auto m = std::int64_t((u >> 2) & ((1ULL << 40) - 1));
                    static const int kDx[4] = {1, 0, -1, 0}, kDy[4] = {0, 1, 0, -1};
                    dx = kDx[u & 3] * m;
                    dy = kDy[u & 3] * m;
                    break;
                }
                case 3: {  // 3-delta: (magnitude << 3) | direction (E N W S NE NW SW SE)
                    const std::uint64_t u = rd_.uint();
                    const auto m = std::int64_t((u >> 3) & ((1ULL << 40) - 1));
                    static const int kDx[8] = {1, 0, -1, 0, 1, -1, -1, 1};
                    static const int kDy[8] = {0, 1, 0, -1, 1, 1, -1, -1};
                    dx = kDx[u & 7] * m;
                    dy = kDy[u & 7] * m;
                    break;
                }
                case 4:
                    rd_.gdelta(dx, dy);
                    break;
                default:
                    throw bad(at, "point-list type " + std::to_string(type) +
                                      " is not supported (0..4 are read)");
            }
            p = {p.x + dx, p.y + dy};
            if (std::llabs(p.x) > (1LL << 40) || std::llabs(p.y) > (1LL << 40))
                throw bad(at, "point list beyond 2^40");
            pts.push_back(p);
        }
        if (type <= 1) {  // Manhattan: one implied vertex closes the polygon
            const bool next_horizontal = (n % 2 == 0) == (type == 0);
            pts.push_back(next_horizontal ? PointNm{0, p.y} : PointNm{p.x, 0});
        }
        if (pts.size() < 3) throw bad(at, "polygon with fewer than 3 vertices");
        return pts;
    }

    void text(std::size_t at) {
        need_cell(at);
        const std::uint8_t info = rd_.byte();
        if (info & kTextRef) throw bad(at, "TEXT by reference number is not supported");
        if (!(info & kTextExplicit)) throw bad(at, "TEXT without its string is not supported");
        for (const auto& [k, v] : parse_info(rd_.string())) g_.info[k] = v;
        if (info & kTextLayer) rd_.uint();
        if (info & kTextType) rd_.uint();
        // Text positions move the modal x/y only for text (separate modal variables).
        if (info & kX) rd_.sint();
        if (info & kY) rd_.sint();
        if (info & kR) throw bad(at, "TEXT with a repetition is not supported");
    }

    Reader rd_;
    FileGeometry g_;
    std::int64_t scale_nm_ = 1;
    std::uint64_t offset_flag_ = 0;
    int cells_ = 0;
    std::optional<std::uint64_t> layer_, datatype_, w_, h_;
    std::optional<std::vector<PointNm>> points_;
    std::int64_t x_ = 0, y_ = 0;
    bool relative_ = false;
    std::vector<PointNm> repetition_;
    bool have_repetition_ = false;
    double expanded_bytes_ = 0.0;  // rings made so far (bytes, estimated), see emit()
    std::set<std::pair<std::uint64_t, std::uint64_t>> layer_seen_;  // g_.layers as numbers
};

}  // namespace

FileGeometry read_oasis(std::string_view bytes) { return OasisParser(bytes).run(); }

}  // namespace pinmask
