// `pinmask search`: find masks for a camera that decode better than random draws. Parses flags
// (and --config), calls optimize/search/search_pipeline, writes the outputs
// (cli/outputs/search_outputs) and prints the summary or io/search_json's JSON.
#include <iostream>
#include <memory>
#include <optional>

#include "cli/command_footers.hpp"
#include "cli/commands.hpp"
#include "cli/options/analytic_setup.hpp"
#include "cli/options/camera_options.hpp"
#include "cli/options/depth_range_flags.hpp"
#include "cli/options/noise_options.hpp"
#include "cli/options/psf_options.hpp"
#include "cli/options/search_options.hpp"
#include "cli/outputs/interrupt.hpp"
#include "cli/outputs/progress.hpp"
#include "cli/outputs/robust_decoder_files.hpp"
#include "cli/outputs/search_outputs.hpp"
#include "cli/outputs/search_snapshot.hpp"
#include "cli/search_cluster.hpp"
#include "core/errors/error.hpp"
#include "io/search_config.hpp"
#include "io/search_json.hpp"
#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/search/mpi/mpi_comm.hpp"
#include "optimize/search/search_pipeline.hpp"

namespace pinmask::cli {

namespace {

SearchPipelineOptions make_options(const SearchCliOptions& o, const CLI::App& cmd) {
    SearchPipelineOptions p = search_pipeline_options(o, cmd);
    if (o.output.empty()) throw InvalidInput("-o/--output: an output folder is required");
    plan_search_outputs(o.output, p.max_holes > 0, o.config);
    return p;
}

void run(const SearchCliOptions& o, const ClusterFlags& cf, const CLI::App& cmd, RankComm& comm,
         bool& started) {
    SearchPipelineOptions p = make_options(o, cmd);
    setup_cluster(cf, comm, checkpoint_config(resolved_config(o, p, {}), comm.size(), cf), o.output,
                  p);
    started = true;  // from here an error may be one rank's alone
    const bool root = comm.rank() == 0;
    if (root && o.config_ranks && *o.config_ranks != comm.size())
        std::cerr << "pinmask search: warning: --config " << o.config << " was written by a run on "
                  << *o.config_ranks << " rank(s), this run has " << comm.size()
                  << ": the chains and islands differ, so this is not the same search\n";
    ProgressLine bar("pinmask search");
    const auto& interrupted = install_interrupt_flag();
    // Rank 0 keeps its best so far on disk while the run lasts (cli/outputs/search_snapshot).
    std::unique_ptr<BestSoFarSnapshot> snapshot;
    if (root) snapshot = attach_best_so_far(p, o.output, &interrupted);
    const SearchPipelineSummary s = run_search_pipeline(
        p, &interrupted,
        [&](const std::string& phase, double fraction, const std::string& text) {
            if (!o.quiet && root) bar.update(fraction, phase + ": " + text, phase);
        },
        [&](const std::string& phase) {
            if (!o.quiet && root) bar.phase(phase);
        });
    if (!root) return;  // rank 0 holds every chain's result and alone writes
    bar.finish();
    if (s.termination == SearchTermination::kInterrupted) {
        std::cerr << "pinmask search: interrupted; writing the best " << s.ranked.size()
                  << " candidate(s) found so far\n";
    }
    if (o.explain) std::cerr << search_explain_text(s, p.allow_spectral_zeros);
    const auto paths = write_search_outputs(o.output, s, resolved_config(o, p, s, comm.size()));
    std::optional<RobustDecoderFiles> decoder;  // robust-filter: rank 1's decoder beside it
    if (p.objective == ObjectiveKind::kRobustFilter && !paths.empty()) {
        const int m = p.tmpl.pattern.n * p.tmpl.psf.pixels_per_cell;
        decoder = write_robust_decoder_files(o.output + "/rank-1.robust-decoder",
                                             s.ranked.front().mask, paths.front().string(),
                                             p.robust, make_scene_prior(p.prior, m), p.noise);
    }
    snapshot->finish();  // the final files supersede best-so-far.mask.json
    if (!o.json) {
        std::cout << search_summary_markdown(s) << "wrote " << paths.size()
                  << " masks, run-log.csv, timing.csv, summary.md and search.config.json"
                  << (s.best_per_holes.empty() ? "" : ", holes.csv/.svg/.png, best-K*.mask.json")
                  << " to " << o.output << "\n"
                  << (decoder ? robust_decoder_usage(*decoder, paths.front().string()) : "");
        return;
    }
    std::optional<std::pair<std::string, std::string>> decoder_files;
    if (decoder) decoder_files = {{decoder->psf_npy, decoder->nsr_npy}};
    std::cout << io::search_json(s, o.output, paths, decoder_files).dump(2) << "\n";
}

void run_search(const SearchCliOptions& o, const ClusterFlags& cf, const CLI::App& cmd) {
    RankComm& comm = world_comm();  // MPI starts here, and only under a launcher
    run_on_ranks(comm, abort_job_if_distributed,
                 [&](bool& started) { run(o, cf, cmd, comm, started); });
}

}  // namespace

void add_search_flags(CLI::App* cmd, const std::shared_ptr<SearchCliOptions>& o) {
    add_camera_options(*cmd, o->camera);
    add_geometry_options(*cmd, o->geometry, &o->holes);
    add_psf_options(*cmd, o->psf);
    cmd->add_option("--strategy", o->strategy,
                    "random: sample valid patterns, keep the best (the paper's approach, the "
                    "baseline); anneal: simulated annealing moving one pinhole at a time")
        ->check(CLI::IsMember({"random", "anneal"}))
        ->capture_default_str();
    cmd->add_option("--time", o->time,
                    "Wall-clock budget of the whole run, re-ranking included (e.g. 20s, 2min)")
        ->capture_default_str();
    cmd->add_option("--evals", o->evals,
                    "Evaluation budget per chain (>= 1) instead of --time: same seed and thread "
                    "count give identical masks, run-log.csv and summary.md");
    cmd->add_option("--threads", o->threads, "Independent chains (default: all cores)");
    cmd->add_option("--seed", o->seed, "Seed of every chain's generator")->capture_default_str();
    cmd->add_option("--top", o->top, "Candidates to keep and write (1..1000)")
        ->capture_default_str();
    add_noise_flags(*cmd, o->noise, "30");
    add_prior_flags(*cmd, o->prior);
    cmd->add_option("--filter", o->filter,
                    "Wiener filter the analytic error assumes: optimal (per-frequency), tuned "
                    "(deconvwnr's NSR tuned per mask, as simulated), nsr:VALUE (fixed NSR) or "
                    "auto (tuned with --photons, optimal with --snr)")
        ->capture_default_str();
    cmd->add_option("--w-analytic", o->w_analytic, "Weight of -analytic Wiener PSNR (dB)")
        ->capture_default_str();
    cmd->add_option("--w-max-sidelobe", o->w_max_sidelobe, "Weight of max sidelobe / K")
        ->capture_default_str();
    cmd->add_option("--w-sidelobe-energy", o->w_sidelobe_energy,
                    "Weight of the integrated sidelobe level")
        ->capture_default_str();
    cmd->add_option("--w-min-spectrum", o->w_min_spectrum, "Weight of -min|P^(k)|/sqrt(K), k != 0")
        ->capture_default_str();
    cmd->add_option("--depth-weight", o->w_depth,
                    "Weight W of the depth term: adds W x 20 log10(worst sigma_u / u) dB, the "
                    "Cramer-Rao bound of score --metrics depth over --depth-from .. --depth-to "
                    "(pinholes' Fisher information summed cell by cell), so W > 0 trades PSNR "
                    "for depth resolution (needs --photons; 0 = the objective without it)")
        ->capture_default_str();
    add_depth_range_flags(*cmd, o->depth_from, o->depth_to, "--depth-weight");
    cmd->add_option("--objective", o->objective,
                    "nominal: the design's analytic Wiener PSNR; robust: its expectation under "
                    "the --robust fabrication errors, decoded with the nominal PSF (needs "
                    "--robust); robust-filter: the same decoded with the filter chosen for the "
                    "errors, written to rank-1.robust-decoder/ (decode --psf, --nsr-map)")
        ->capture_default_str();
    cmd->add_option("--robust", o->robust, kRobustFlagHelp);
    cmd->add_option("--keep-out", o->keep_out, "Cells no pinhole may use: none | border")
        ->capture_default_str();
    cmd->add_flag("--allow-spectral-zeros", o->allow_spectral_zeros,
                  "Keep patterns whose |P^(k)| < 1e-3 sqrt(K) at a frequency the kernel passes "
                  "(flagged in the summary); by default they are rejected");
    cmd->add_option("--rerank-scenes", o->rerank_scenes,
                    "Held-out scenes for the final re-ranking (not natural with the natural prior)")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--rank-by", o->rank_by,
                    "Decoder whose simulated PSNR orders the re-ranked candidates: wiener, or tv "
                    "(TV-L2 with lambda tuned per mask on the re-ranking scenes; slower)")
        ->capture_default_str();
    cmd->add_flag("!--no-rerank-tv", o->rerank_tv, "Skip the TV reconstructions when re-ranking");
    cmd->add_flag("--no-rerank", o->no_rerank, "Skip the simulated re-ranking stage");
    cmd->add_option("-o,--output", o->output, "Output folder (created)")->required();
    cmd->add_flag("--json", o->json, "Print the ranking as JSON on stdout");
    cmd->add_flag("--quiet", o->quiet, "No progress line on stderr");
    cmd->add_flag("--explain", o->explain,
                  "Say on stderr which frequencies the prior makes irrelevant and what was "
                  "skipped");
}

void add_search(CLI::App& app) {
    auto o = std::make_shared<SearchCliOptions>();
    auto cf = std::make_shared<ClusterFlags>();
    auto* cmd = app.add_subcommand(
        "search",
        "Search random sparse cyclic patterns under the spacing rule for the mask that decodes "
        "best. The objective is the analytic expected Wiener PSNR (closed form from the OTF, the "
        "scene prior and the noise model: Gaussian --snr or the photon model --photons) plus "
        "optional sidelobe and spectrum terms; patterns with a spectral zero are rejected; the "
        "top candidates are re-ranked by simulated Wiener or TV reconstruction of held-out "
        "scenes, all inside --time.");
    add_search_flags(cmd, o);
    cmd->add_option("--config", o->config,
                    "Settings of an earlier run (its search.config.json, or a subset of its "
                    "keys); flags given here override them")
        ->check(CLI::ExistingFile);
    add_cluster_flags(*cmd, *cf);
    cmd->footer(std::string(kSearchFooter) + "\n" + kRobustFooter + kSearchRobustNote);
    cmd->callback([o, cf, cmd] {
        if (!o->config.empty()) apply_config(io::read_search_config(o->config), *cmd, *o);
        run_search(*o, *cf, *cmd);
    });
}

}  // namespace pinmask::cli
