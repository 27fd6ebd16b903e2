// The one comparison of a fabrication file with its design, used by `pinmask export` (every
// file it writes is read back from disk before it is committed) and by `pinmask check` (a file
// given by a user, compared with the mask named by its sidecar or by --mask).
// Two ring sets are equal when their canonical forms are (export/layout/rings canonical_rings);
// else the rings found in only one of them are compared by exact XOR area (export/layout/xor_area:
// the common rings cancel, because rings of one set never overlap). The file's geometry hash (info
// "hash") must be the design's.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "export/formats/read_any.hpp"
#include "export/layout/layout.hpp"
#include "export/layout/rings.hpp"

namespace pinmask {

struct ReadBack {
    std::size_t file_rings = 0;    // canonical (non-degenerate) rings in the file
    std::size_t design_rings = 0;  // and in the design
    std::size_t only_file = 0;     // rings of the file not among the design's, and vice versa
    std::size_t only_design = 0;
    double xor_area_nm2 = 0.0;  // exact XOR area of those (0 when the sets are identical)
    std::string file_hash;      // info "hash" of the file ("" when it has none)
    std::string design_hash;
    bool identical() const { return only_file == 0 && only_design == 0; }
    bool hash_ok() const { return file_hash == design_hash; }
    // Geometry within max_xor_nm2 and the hash the design's.
    bool ok(double max_xor_nm2 = 0.0) const { return xor_area_nm2 <= max_xor_nm2 && hash_ok(); }
    // "42 polygons identical to the design", "same area as the design (XOR 0), 42 polygons", or
    // what differs.
    std::string describe() const;
};

// Compares file rings with design rings (any order, either orientation).
ReadBack compare_rings(const std::vector<Ring>& file_rings, const std::vector<Ring>& design_rings,
                       std::string file_hash, std::string design_hash);

// A file's geometry against a layout: every ring (pinholes or opaque pieces, marks, label) with
// the layout's (export/layout/geometry all_rings); native circles in the file with the layout's
// circles (exactly: same centre and diameter), its rings then with the annotations.
ReadBack compare_with_layout(const FileGeometry& file, const Layout& design);

// Reads `bytes` in `format` and compares them with the layout (compare_with_layout).
ReadBack read_back(std::string_view bytes, FabFormat format, const Layout& design);

// Export's verification: read_back that must match exactly (XOR 0, the mask hash present);
// throws RuntimeFailure saying what differs. Returns describe().
std::string verify_written(std::string_view bytes, FabFormat format, const Layout& design);

}  // namespace pinmask
