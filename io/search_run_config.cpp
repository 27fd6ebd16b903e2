#include "io/search_run_config.hpp"

#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/files/output_set.hpp"
#include "io/json_strict.hpp"
#include "io/optics_json.hpp"
#include "io/search_config.hpp"
#include "optimize/metrics/mask_metrics.hpp"

namespace pinmask::io {
namespace {

using json_strict::finite_or_null;

nlohmann::ordered_json noise_config(const NoiseModel& m) {
    if (m.kind != NoiseKind::kPhoton) return {{"model", "gaussian"}, {"snr_db", m.snr_db}};
    return {{"model", "photon"},
            {"photons_per_pinhole", m.photons_per_pinhole},
            {"read_noise_e", m.read_noise_e},
            {"dark_current_e", m.dark_current_e},
            {"full_well_e", finite_or_null(m.full_well_e)},
            {"adc_bits", m.adc_bits},
            {"film_optical_density", finite_or_null(m.film_optical_density)}};
}

}  // namespace

nlohmann::ordered_json resolved_search_config(const SearchPipelineOptions& p,
                                              const SearchRunTexts& t,
                                              const std::string& kernel_resolved, int ranks) {
    nlohmann::ordered_json prior{{"family", prior_kind_name(p.prior.kind)},
                                 {"scenes", p.prior.count}};
    if (p.prior.kind == PriorKind::kFiles) {
        prior["files"] = nlohmann::ordered_json::array();
        for (const auto& f : p.prior.files) prior["files"].push_back(f.string());
    }
    nlohmann::ordered_json out{
        {"format", kSearchConfigFormat},
        {"version", kSearchConfigVersion},
        {"generator", kSearchGenerator},
        {"strategy", t.strategy},
        {"time", p.search.max_evaluations > 0 ? nlohmann::ordered_json(nullptr)
                                              : nlohmann::ordered_json(t.time)},
        {"evaluations_per_chain", p.search.max_evaluations},
        {"ranks", ranks},
        {"threads", p.search.threads},
        {"seed", t.seed},
        {"top", t.top},
        {"grid", p.tmpl.pattern.n},
        {"holes", p.holes},
        {"max_holes", p.max_holes},
        {"tiles", p.tmpl.pattern.tiles_rows},
        {"min_spacing_cells", p.tmpl.pattern.min_spacing_cells},
        {"keep_out", t.keep_out},
        {"pixels_per_cell", p.tmpl.psf.pixels_per_cell},
        {"kernel_requested", p.tmpl.psf.kernel.model},
        {"kernel_resolved", kernel_resolved},
        {"kernel_path", p.tmpl.psf.kernel.measured_path},
        {"noise", noise_config(p.noise)},
        {"filter", t.filter},
        {"prior", prior},
        {"weights",
         {{"analytic_wiener", t.w_analytic},
          {"max_sidelobe", t.w_max_sidelobe},
          {"sidelobe_energy", t.w_sidelobe_energy},
          {"min_spectrum", t.w_min_spectrum}}},
        {"rerank_scenes", t.rerank_scenes},
        {"rerank_tv", p.rerank_tv},
        {"allow_spectral_zeros", p.allow_spectral_zeros},
        {"rank_by", t.rank_by},
        {"objective", t.objective},
        {"robust", t.robust},
        {"optics", optics_to_json<nlohmann::ordered_json>(p.tmpl.camera)}};
    if (t.w_depth > 0.0) {
        out["weights"]["depth"] = t.w_depth;
        out["depth_range"] = {{"from_m", p.depth_range.from_m}, {"to_m", p.depth_range.to_m}};
    }
    return out;
}

nlohmann::ordered_json checkpoint_config(nlohmann::ordered_json resolved, int ranks,
                                         std::int64_t migrate_every,
                                         std::int64_t checkpoint_every) {
    for (const char* k : {"time", "generator", "kernel_resolved"}) resolved.erase(k);
    resolved["ranks"] = ranks;
    resolved["migrate_every"] = migrate_every;
    resolved["checkpoint_every"] = checkpoint_every;
    return resolved;
}

decltype(IslandOptions::checkpoint) checkpoint_writer(const std::filesystem::path& path,
                                                      const nlohmann::ordered_json& config) {
    // Checked now like every output (not a device, a pipe, a folder or a file this run read),
    // not at the first boundary, after the work.
    check_output_path(path, field_ref("checkpoint"));
    return [path, config](std::int64_t segment, std::int64_t every,
                          const std::vector<ChainState>& states) {
        SearchCheckpointFile c;
        c.config = config;
        c.segment = segment;
        c.every = every;
        c.chains = states;
        write_checkpoint(path, c);
    };
}

SearchCheckpointFile checkpoint_to_resume(const std::filesystem::path& path,
                                          const nlohmann::ordered_json& config,
                                          const std::filesystem::path& checkpoint) {
    SearchCheckpointFile c = read_checkpoint(path);
    // A run that resumes from its own checkpoint file (a job requeued with the same command)
    // supersedes it at its next boundary, atomically: that one input may be replaced.
    if (!checkpoint.empty() && same_file(path, checkpoint)) release_input(path);
    const std::vector<std::string> diff = differing_keys(config, c.config);
    if (!diff.empty()) {
        std::string keys;
        for (const std::string& k : diff) keys += (keys.empty() ? "" : ", ") + k;
        throw invalid_field(field_ref("resume"), path.string(),
                            "the checkpoint is of another configuration; differing keys: " + keys);
    }
    // The boundaries of this run: every gcd(migrate_every, checkpoint_every) evaluations per
    // chain, written only while some chain has budget left, each chain at or past the boundary.
    const auto count = [&](const char* key) { return config.value(key, std::int64_t{0}); };
    const std::int64_t every = std::gcd(count("migrate_every"), count("checkpoint_every"));
    const std::int64_t budget = count("evaluations_per_chain");
    const auto refuse = [&](const std::string& what) {
        throw invalid_field(field_ref("resume"), path.string(), what);
    };
    if (c.every != every) {
        refuse("evaluations_between_boundaries = " + std::to_string(c.every) +
               ": this run's boundaries fall every " + std::to_string(every) +
               " evaluations per chain");
    }
    if (every > 0 && budget > 0 && c.segment > (budget - 1) / every) {
        refuse("segment = " + std::to_string(c.segment) + ": this run's last boundary is " +
               std::to_string((budget - 1) / every) + " (" + std::to_string(budget) +
               " evaluations per chain, a boundary every " + std::to_string(every) + ")");
    }
    for (std::size_t i = 0; budget > 0 && i < c.chains.size(); ++i) {
        if (c.chains[i].evaluations < c.segment * every) {
            refuse("chains[" + std::to_string(i) +
                   "].evaluations = " + std::to_string(c.chains[i].evaluations) + ": at boundary " +
                   std::to_string(c.segment) + " every chain has made at least " +
                   std::to_string(c.segment * every));
        }
    }
    return c;
}

}  // namespace pinmask::io
