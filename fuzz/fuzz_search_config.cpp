// Fuzzes the search configuration reader (io/search_config, `pinmask search --config FILE`):
// any bytes give a SearchConfig or InvalidInput, never another exception (syntax errors and
// number overflow included). An accepted configuration's values obey the reader's rules.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/errors/error.hpp"
#include "fuzz/fuzz_support.hpp"
#include "io/search_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace pinmask;
    io::SearchConfig c;
    try {
        c = io::parse_search_config(std::string(fuzz::as_text(data, size)));
    } catch (const InvalidInput&) {
        return 0;
    }
    for (const auto& v : {c.grid, c.holes, c.tiles, c.top, c.pixels_per_cell, c.prior_scenes})
        if (v && *v < 1) fuzz::invariant_failed("a count below 1 accepted");
    if (c.threads && *c.threads < 0) fuzz::invariant_failed("negative threads accepted");
    if (c.evaluations_per_chain && *c.evaluations_per_chain < 0)
        fuzz::invariant_failed("negative evaluation budget accepted");
    if (c.min_spacing_cells && !(*c.min_spacing_cells > 0 && std::isfinite(*c.min_spacing_cells)))
        fuzz::invariant_failed("spacing not positive and finite");
    for (const auto& w :
         {c.snr_db, c.w_analytic, c.w_max_sidelobe, c.w_sidelobe_energy, c.w_min_spectrum})
        if (w && !std::isfinite(*w)) fuzz::invariant_failed("non-finite number accepted");
    if (c.strategy && *c.strategy != "random" && *c.strategy != "anneal")
        fuzz::invariant_failed("unknown strategy accepted");
    if (c.optics && !(c.optics->sensor_cols >= 1 && c.optics->sensor_rows >= 1))
        fuzz::invariant_failed("sensor below 1 pixel accepted");
    return 0;
}
