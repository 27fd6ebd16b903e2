// `pinmask check` of a fabrication file as a library call: the file's geometry (export/read_any)
// split into pinhole polygons and annotations, compared with its design (export/read_back) when
// the design is known, and checked against design rules (export/drc).
//   with a design and whole_layout (the export sidecar gave every layout setting): every ring
//     and circle is compared with the design's (marks and label included), and the file splits
//     as the design does;
//   with a design only (--mask without a sidecar): rings inside the outline of the design's
//     polygons are the pinholes, compared with the design's polygons;
//   without a design: rings inside `outline` (if given) are the pinholes, all rings otherwise.
#pragma once

#include <optional>

#include "export/drc.hpp"
#include "export/layout.hpp"
#include "export/read_back.hpp"
#include "export/rings.hpp"

namespace pinmask {

struct FileCheckOptions {
    const Layout* design = nullptr;  // the layout the file was exported from (may be null)
    bool whole_layout = false;       // compare marks and label too (settings from a sidecar)
    std::optional<BoxNm> outline;    // without a design: where the pinholes are
    DrcRules rules;
    double max_xor_nm2 = 0.0;
};

struct FileCheck {
    Layout layout;                       // the file as a layout (tone from its info)
    std::optional<ReadBack> comparison;  // with a design
    DrcReport drc;
    bool clean() const {
        // (a foreign file without a mask hash is compared by geometry alone)
        return drc.clean() &&
               (!comparison || (comparison->xor_area_nm2 <= max_xor_nm2 &&
                                (comparison->file_hash.empty() || comparison->hash_ok())));
    }
    double max_xor_nm2 = 0.0;
};

FileCheck check_file_geometry(const FileGeometry& file, const FileCheckOptions& options);

}  // namespace pinmask
