// `pinmask sweep SWEEP.json -o DIR`: one search per design point. Parses the sweep
// file (io/sweep_config), turns every point into search pipeline options the way `pinmask search
// --config` does (cli/options/search_options), runs optimize/search/sweep (over MPI ranks when
// under mpirun) and writes the outputs on rank 0 (cli/outputs/sweep_outputs).
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/options/search_options.hpp"
#include "cli/outputs/progress.hpp"
#include "cli/outputs/sweep_outputs.hpp"
#include "cli/sweep_help.hpp"
#include "core/errors/error.hpp"
#include "core/files/output_set.hpp"
#include "core/version.hpp"
#include "design/pattern/packing_bound.hpp"
#include "io/sweep_config.hpp"
#include "optimize/search/mpi/mpi_comm.hpp"
#include "optimize/search/sweep.hpp"

namespace pinmask::cli {
namespace {

struct SweepCliOptions {
    std::string sweep, output;
    bool json = false, quiet = false;
};

// The pipeline options of one point: the search flags on an app that is never parsed, filled
// from the point's configuration by the same code as `pinmask search --config`.
SearchPipelineOptions point_options(const io::SweepPoint& point, std::size_t index,
                                    nlohmann::ordered_json& resolved) {
    CLI::App shadow;
    auto o = std::make_shared<SearchCliOptions>();
    add_search_flags(&shadow, o);
    try {
        apply_config(point.config, shadow, *o);
        o->threads = point.config.threads.value_or(1);
        SearchPipelineOptions p = search_pipeline_options(*o, shadow);
        // A proven-infeasible K fails here, before any rank starts work, not at its point.
        const PackingUpperBound most =
            packing_upper_bound(p.tmpl.pattern.n, p.tmpl.pattern.min_spacing_cells);
        if (p.holes > most.count)
            throw invalid_field(
                "holes", std::to_string(p.holes),
                "at most " + std::to_string(most.count) + " pinholes fit (" + most.reason + ")");
        SearchPipelineSummary kernel_only;
        kernel_only.kernel_resolved = p.tmpl.psf.kernel.model;
        resolved = resolved_config(*o, p, kernel_only);
        resolved["generator"] = PINMASK_GENERATOR("sweep");
        return p;
    } catch (const InvalidInput& e) {
        std::string label;
        for (const auto& v : point.values)
            label += (label.empty() ? "" : ", ") + v.key + " = " + v.text;
        throw InvalidInput("SWEEP point " + std::to_string(index) + " (" + label +
                           "): " + e.what());
    }
}

void run(const SweepCliOptions& o) {
    // Every rank reads and checks the file and plans the outputs: a bad file or -o is exit 2
    // on every rank before any rank starts work.
    const io::SweepConfig sweep = io::read_sweep_config(o.sweep);
    std::vector<SearchPipelineOptions> options;
    std::vector<nlohmann::ordered_json> configs(sweep.points.size());
    for (std::size_t i = 0; i < sweep.points.size(); ++i)
        options.push_back(point_options(sweep.points[i], i, configs[i]));
    std::vector<NamedPath> outputs;
    for (const auto& p : sweep_table_paths(o.output, sweep.points.size()))
        outputs.push_back({"-o", p, true});
    plan_outputs({{"SWEEP", o.sweep}}, outputs);

    ProgressLine bar;
    const std::vector<SweepPointResult> results =
        run_sweep(world_comm(), options, [&](int done, int count, int index) {
            if (o.quiet) return;
            const std::string text = "point " + std::to_string(index) + " done (" +
                                     std::to_string(done) + "/" + std::to_string(count) + ")";
            if (bar.enabled())
                bar.update(double(done) / count, text);
            else
                std::cerr << "pinmask sweep: " << text << "\n";
        });
    bar.finish();
    if (results.empty()) return;  // a worker rank: rank 0 writes
    std::vector<SweepRow> rows;
    for (std::size_t i = 0; i < results.size(); ++i) {
        configs[i]["kernel_resolved"] = results[i].kernel_resolved;
        rows.push_back({&sweep.points[i], &options[i], configs[i], results[i]});
    }
    const auto plots = write_sweep_outputs(o.output, sweep, rows);
    if (!o.json) {
        std::cout << sweep_markdown(sweep, rows) << "wrote sweep.csv, sweep.md, " << results.size()
                  << " masks and " << plots.size() << " plot files to " << o.output << "\n";
        return;
    }
    nlohmann::ordered_json j{{"output", o.output}, {"points", results.size()}};
    j["keys"] = sweep.keys;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        nlohmann::ordered_json r{{"point", i}};
        for (const auto& v : sweep.points[i].values) r[v.key] = v.text;
        r["objective"] = results[i].objective;
        r["evaluations"] = results[i].evaluations;
        r["geometry_hash"] = geometry_hash(sweep_best_mask(options[i], results[i]));
        for (const auto& [k, v] : results[i].scores) r[k] = v;
        j["rows"].push_back(r);
    }
    for (const auto& p : plots) j["plots"].push_back(p.string());
    std::cout << j.dump(2) << "\n";
}

}  // namespace

void add_sweep(CLI::App& app) {
    auto o = std::make_shared<SweepCliOptions>();
    auto* cmd = app.add_subcommand(
        "sweep",
        "Design sweep: one search per design point of a grid (or list) over any search "
        "options, e.g. pinhole count x pinhole size x light level; writes a table, the best "
        "mask per point and PSNR plots. Under mpirun the points are shared among the ranks.");
    cmd->add_option("SWEEP", o->sweep, "The sweep file (JSON; see below)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("-o,--output", o->output, "Output folder (created)")->required();
    cmd->add_flag("--json", o->json, "Print the table as JSON on stdout");
    cmd->add_flag("--quiet", o->quiet, "No progress on stderr");
    cmd->footer(kSweepFooter);
    cmd->callback([o] { run(*o); });
}

}  // namespace pinmask::cli
