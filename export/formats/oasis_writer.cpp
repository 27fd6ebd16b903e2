#include "export/formats/oasis_writer.hpp"

#include <optional>

#include "core/errors/error.hpp"
#include "export/formats/oasis_codec.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/repetition.hpp"
#include "export/layout/rings.hpp"

namespace pinmask {
namespace {

using namespace oasis;

bool is_box(const Ring& r) {
    if (r.size() != 4) return false;
    const bool a = r[0].y == r[1].y && r[1].x == r[2].x && r[2].y == r[3].y && r[3].x == r[0].x;
    const bool b = r[0].x == r[1].x && r[1].y == r[2].y && r[2].x == r[3].x && r[3].y == r[0].y;
    return a || b;
}

// Modal state of the writer (mirrors what a reader keeps, so unchanged fields are omitted).
struct Modal {
    std::optional<std::int64_t> w, h;
    std::optional<Ring> points;  // the last polygon's shape (first vertex at the origin)
    std::int64_t x = 0, y = 0;   // XYRELATIVE: the last element's position
    bool layer_set = false;
    bool repetition_set = false;
};

class CellWriter {
  public:
    CellWriter(Writer& w, const OasisOptions& o) : w_(w), o_(o) {}

    // A ring placed at `at` (its first vertex; for boxes the lower-left corner), with the
    // grid repetition when cols * rows > 1.
    void element(const Ring& ring, int cols, int rows, std::int64_t px, std::int64_t py) {
        const bool rep = cols * rows > 1;
        std::uint8_t info = 0;
        if (!m_.layer_set) info |= kL | kD;
        if (rep) info |= kR;
        if (is_box(ring)) {
            BoxNm b = bounding_box({ring});
            const std::int64_t bw = b.x1 - b.x0, bh = b.y1 - b.y0;
            const bool square = bw == bh;
            if (square) info |= kS;
            if (m_.w != bw) info |= kW;
            if (!square && m_.h != bh) info |= kH;
            // (a square sets both modal width and height)
            info |= kX | kY;
            w_.byte(kRectangle);
            w_.byte(info);
            fields(info);
            if (info & kW) w_.uint(std::uint64_t(bw));
            if (info & kH) w_.uint(std::uint64_t(bh));
            position(b.x0, b.y0);
            m_.w = bw;
            m_.h = bh;
        } else {
            Ring shape = ring;
            for (PointNm& p : shape) p = {p.x - ring[0].x, p.y - ring[0].y};
            const bool same = m_.points && *m_.points == shape;
            std::uint8_t pinfo = std::uint8_t(info & (kL | kD | kR)) | kX | kY;
            if (!same) pinfo |= kP;
            w_.byte(kPolygon);
            w_.byte(pinfo);
            fields(pinfo);
            if (!same) {
                w_.uint(kPointListGeneral);
                w_.uint(shape.size() - 1);
                for (std::size_t i = 1; i < shape.size(); ++i)
                    w_.gdelta(shape[i].x - shape[i - 1].x, shape[i].y - shape[i - 1].y);
                m_.points = std::move(shape);
            }
            position(ring[0].x, ring[0].y);
        }
        if (rep) repetition(cols, rows, px, py);
    }

    void text(const std::string& s, PointNm at) {
        std::uint8_t info = kTextExplicit | kX | kY | kTextLayer | kTextType;
        w_.byte(kText);
        w_.byte(info);
        w_.string(s);
        w_.uint(std::uint64_t(o_.layer));
        w_.uint(0);
        // Text has its own modal position (text-x, text-y), 0 at the start of the cell.
        w_.sint(at.x);
        w_.sint(at.y);
    }

  private:
    void fields(std::uint8_t info) {
        if (info & kL) w_.uint(std::uint64_t(o_.layer));
        if (info & kD) w_.uint(std::uint64_t(o_.datatype));
        m_.layer_set = true;
    }
    void position(std::int64_t x, std::int64_t y) {  // XYRELATIVE: deltas
        w_.sint(x - m_.x);
        w_.sint(y - m_.y);
        m_.x = x;
        m_.y = y;
    }
    void repetition(int cols, int rows, std::int64_t px, std::int64_t py) {
        if (m_.repetition_set) {
            w_.uint(0);  // the modal repetition again
            return;
        }
        if (cols >= 2 && rows >= 2) {
            w_.uint(1);
            w_.uint(std::uint64_t(cols - 2));
            w_.uint(std::uint64_t(rows - 2));
            w_.uint(std::uint64_t(px));
            w_.uint(std::uint64_t(py));
        } else if (cols >= 2) {
            w_.uint(2);
            w_.uint(std::uint64_t(cols - 2));
            w_.uint(std::uint64_t(px));
        } else {
            w_.uint(3);
            w_.uint(std::uint64_t(rows - 2));
            w_.uint(std::uint64_t(py));
        }
        m_.repetition_set = true;
    }

    Writer& w_;
    const OasisOptions& o_;
    Modal m_;
};

}  // namespace

std::string oasis_file(const Layout& layout, const OasisOptions& o) {
    if (o.layer < 0 || o.datatype < 0)
        throw invalid_field("layer", std::to_string(o.layer) + "/" + std::to_string(o.datatype),
                            "OASIS layer and datatype must be >= 0");
    Writer w;
    w.raw(kMagic);
    w.byte(kStart);
    w.string("1.0");
    w.byte(0);                               // real, type 0: positive whole number
    w.uint(1000);                            // grid steps per micron: 1 nm
    w.uint(0);                               // offset flag 0: the table offsets follow here
    for (int i = 0; i < 12; ++i) w.uint(0);  // six tables, none present
    w.byte(kCellByName);
    w.string("PINMASK_" + layout.mask_hash);
    w.byte(kXyRelative);
    CellWriter cell(w, o);
    const Repetition r = o.repetitions ? find_repetition(layout.polygons, layout.active_area,
                                                         layout.tiles_rows, layout.tiles_cols)
                                       : Repetition{};
    if (r.cols * r.rows > 1) {
        for (const Placement& p : r.placements) {
            Ring ring = r.shapes[p.shape];
            for (PointNm& v : ring) v = {v.x + p.at.x, v.y + p.at.y};
            cell.element(ring, r.cols, r.rows, r.pitch_x_nm, r.pitch_y_nm);
        }
    } else {
        for (const Ring& ring : layout.polygons) cell.element(ring, 1, 1, 0, 0);
    }
    for (const Ring& ring : layout.annotations) cell.element(ring, 1, 1, 0, 0);
    cell.text("pinmask " + layout_info(layout, "nm") + " user_unit=" + fab_unit_name(o.unit),
              {layout.extent.x0, layout.extent.y0});
    w.end_record();
    return std::move(w.bytes());
}

}  // namespace pinmask
