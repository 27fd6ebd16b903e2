#include "export/pipeline/read_back.hpp"

#include <algorithm>
#include <iterator>

#include "core/errors/error.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/xor_area.hpp"

namespace pinmask {
namespace {

bool ring_less(const Ring& a, const Ring& b) {
    return std::lexicographical_compare(
        a.begin(), a.end(), b.begin(), b.end(),
        [](const PointNm& p, const PointNm& q) { return p.x != q.x ? p.x < q.x : p.y < q.y; });
}

std::string area_um2(double nm2) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g um^2", nm2 * 1e-6);
    return buf;
}

}  // namespace

std::string ReadBack::describe() const {
    std::string s;
    if (identical())
        s = std::to_string(file_rings) + " polygons identical to the design";
    else if (xor_area_nm2 == 0)
        s = "same area as the design (XOR 0), " + std::to_string(file_rings) + " polygons";
    else
        s = std::to_string(only_file) + " rings only in the file, " + std::to_string(only_design) +
            " only in the design, XOR area " + area_um2(xor_area_nm2);
    if (!hash_ok())
        s += file_hash.empty() ? "; the file carries no mask hash"
                               : "; file hash " + file_hash + " != design " + design_hash;
    return s;
}

ReadBack compare_rings(const std::vector<Ring>& file_rings, const std::vector<Ring>& design_rings,
                       std::string file_hash, std::string design_hash) {
    const std::vector<Ring> got = canonical_rings(file_rings);
    const std::vector<Ring> want = canonical_rings(design_rings);
    ReadBack r;
    r.file_rings = got.size();
    r.design_rings = want.size();
    r.file_hash = std::move(file_hash);
    r.design_hash = std::move(design_hash);
    if (got == want) return r;
    std::vector<Ring> only_file, only_design;
    std::set_difference(got.begin(), got.end(), want.begin(), want.end(),
                        std::back_inserter(only_file), ring_less);
    std::set_difference(want.begin(), want.end(), got.begin(), got.end(),
                        std::back_inserter(only_design), ring_less);
    r.only_file = only_file.size();
    r.only_design = only_design.size();
    r.xor_area_nm2 = xor_area_nm2(only_file, only_design);
    return r;
}

ReadBack compare_with_layout(const FileGeometry& g, const Layout& design) {
    const auto hash = g.info.find("hash");
    std::string file_hash = hash == g.info.end() ? "" : hash->second;
    if (g.circles.empty())
        return compare_rings(g.rings, all_rings(design), std::move(file_hash), design.mask_hash);
    // Native circles stand for the pinhole polygons: circles against circles (exact), rings
    // against the annotations.
    ReadBack r =
        compare_rings(g.rings, design.circles.empty() ? all_rings(design) : design.annotations,
                      std::move(file_hash), design.mask_hash);
    std::vector<CircleNm> got = g.circles, want = design.circles;
    std::sort(got.begin(), got.end());
    std::sort(want.begin(), want.end());
    std::vector<CircleNm> only_file, only_design;
    std::set_difference(got.begin(), got.end(), want.begin(), want.end(),
                        std::back_inserter(only_file));
    std::set_difference(want.begin(), want.end(), got.begin(), got.end(),
                        std::back_inserter(only_design));
    r.file_rings += got.size();
    r.design_rings += want.size();
    r.only_file += only_file.size();
    r.only_design += only_design.size();
    // Differing circles are disjoint from everything else in their sets; their XOR is bounded
    // by the sum of their areas, reported as such (a circle matches exactly or not at all).
    constexpr double kQuarterPi = 0.78539816339744830962;
    for (const auto* set : {&only_file, &only_design})
        for (const CircleNm& c : *set)
            r.xor_area_nm2 += kQuarterPi * double(c.diameter_nm) * double(c.diameter_nm);
    return r;
}

ReadBack read_back(std::string_view bytes, FabFormat format, const Layout& design) {
    return compare_with_layout(read_fabrication_bytes(bytes, format), design);
}

std::string verify_written(std::string_view bytes, FabFormat format, const Layout& design) {
    const ReadBack r = read_back(bytes, format, design);
    if (!r.ok())
        throw RuntimeFailure(fab_format_name(format) +
                             " file read back differs from the design: " + r.describe());
    return "read back: " + r.describe();
}

}  // namespace pinmask
