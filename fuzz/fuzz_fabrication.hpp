// The body shared by the fabrication-file reader targets (fuzz_gds, fuzz_dxf, fuzz_gerber,
// fuzz_svg): read the bytes, then do what `pinmask check FILE` does with the geometry (bounding
// box, design-rule check), so the consumers of the readers' output are fuzzed too. The DRC runs
// only where its documented precondition holds (|coordinate| <= kMaxCoordNm; otherwise it must
// refuse with InvalidInput) and on inputs of at most kMaxDrcVertices vertices, which keeps the
// executions fast enough for the fuzzer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/errors/error.hpp"
#include "export/layout/rings.hpp"
#include "export/pipeline/drc.hpp"
#include "fuzz/fuzz_support.hpp"

namespace pinmask::fuzz {

inline constexpr std::size_t kMaxDrcVertices = 4096;

template <typename Reader>
int fuzz_fabrication_reader(Reader read, const std::uint8_t* data, std::size_t size) {
    FileGeometry g;
    try {
        g = read(as_text(data, size));
    } catch (const InvalidInput&) {
        return 0;
    }
    std::size_t vertices = 0;
    for (const Ring& r : g.rings) vertices += r.size();
    const BoxNm box = bounding_box(g.rings);
    if (box.x0 > box.x1 || box.y0 > box.y1) invariant_failed("bounding box");
    if (vertices > kMaxDrcVertices) return 0;
    try {
        const DrcReport report = run_drc(g.rings, DrcRules{});
        (void)report.clean();
    } catch (const InvalidInput&) {
        const bool in_range = box.x0 >= -kMaxCoordNm && box.y0 >= -kMaxCoordNm &&
                              box.x1 <= kMaxCoordNm && box.y1 <= kMaxCoordNm;
        if (in_range) invariant_failed("run_drc refused coordinates within range");
    }
    return 0;
}

}  // namespace pinmask::fuzz
