// Every command with a library request takes its flags' defaults from a default-constructed
// request: for each setting the request holds and a flag sets, the default the flag shows in
// `pinmask CMD --help` (CLI11's `--flag TYPE=DEFAULT`) equals the request's value. The flag is
// found through the command line's own spelling table (cli/options/flag_names), so a renamed
// flag or field fails here. tests/python/test_parity_defaults.py checks Python's keyword defaults
// against the same
// --help column, so the three agree.
#include <doctest/doctest.h>

#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli/options/flag_names.hpp"
#include "decode/calibrate/calibrate_run.hpp"
#include "decode/capture/decode_request.hpp"
#include "decode/depthmap/depthmap_run.hpp"
#include "decode/solvers/decode_method.hpp"
#include "design/optics/design_run.hpp"
#include "export/pipeline/export_request.hpp"
#include "optimize/metrics/score_run.hpp"
#include "report/compare_run.hpp"
#include "tests/support/cli_run.hpp"

namespace {

using namespace pinmask;

// A request's setting: the field as the libraries name it (the flag table's key) and its
// default as text.
struct Setting {
    std::string field, value;
};

std::string text(double v) {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
}
std::string text(const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& item : items) out += (out.empty() ? "" : ",") + item;
    return out;
}

// Numbers compare as numbers ("1e-3" is "0.001"), anything else as text.
bool same_default(const std::string& shown, const std::string& expected) {
    char* end_a = nullptr;
    char* end_b = nullptr;
    const double a = std::strtod(shown.c_str(), &end_a);
    const double b = std::strtod(expected.c_str(), &end_b);
    if (!shown.empty() && !expected.empty() && *end_a == '\0' && *end_b == '\0') return a == b;
    return shown == expected;
}

// flag -> the default `pinmask COMMAND --help` shows ("" when it shows none).
std::map<std::string, std::string> help_defaults(const std::string& command) {
    const test::CliResult r = test::run_cli(command + " --help");
    REQUIRE(r.exit_code == 0);
    // "  -o,--output-dir TEXT=depthmap_out   Folder...": the names, a type (which may hold
    // single spaces, "INT:INT in [0 - 12]"), maybe "=DEFAULT", then two spaces and the text.
    std::map<std::string, std::string> out;
    std::istringstream in(r.out);
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("  -", 0) != 0) continue;
        const std::string column = line.substr(2, line.find("  ", 2) - 2);
        const std::size_t space = column.find(' ');
        const std::size_t eq = column.find('=');
        const std::string shown =
            eq == std::string::npos ? "" : column.substr(eq + 1, column.find(' ', eq) - eq - 1);
        std::istringstream names(column.substr(0, space));
        for (std::string name; std::getline(names, name, ',');) out[name] = shown;
    }
    return out;
}

// Checks every setting's flag default in the command's --help.
void check_defaults(const std::string& command, const std::vector<Setting>& settings) {
    const std::map<std::string, std::string> shown = help_defaults(command);
    for (const Setting& s : settings) {
        const std::optional<std::string> flag = cli::flag_spelling(s.field);
        INFO(command << ": field " << s.field);
        REQUIRE(flag.has_value());
        INFO("flag " << *flag);
        const auto it = shown.find(*flag);
        REQUIRE(it != shown.end());
        INFO("shown [" << it->second << "], the request's [" << s.value << "]");
        CHECK(same_default(it->second, s.value));
    }
}

}  // namespace

TEST_CASE("the default comparison reads numbers as numbers and text as text") {
    CHECK(same_default("0.001", "1e-3"));
    CHECK(same_default("16", text(16.0)));
    CHECK_FALSE(same_default("0.01", "0.1"));
    CHECK_FALSE(same_default("", "0"));  // a default the flag does not show is not the request's
    CHECK(same_default("auto", "auto"));
    CHECK_FALSE(same_default("auto", "tuned"));
}

TEST_CASE("design's flags default to DesignRequest's settings") {
    const DesignRequest q;
    check_defaults("design", {{"grid", text(q.geometry.n)},
                              {"holes", text(q.geometry.holes)},
                              {"tiles", text(q.geometry.tiles_rows)},
                              {"spacing", text(q.spacing_cells)},
                              {"kernel", q.kernel},
                              {"lsi_tolerance_px", text(q.lsi_tolerance_px)}});
}

TEST_CASE("score's flags default to ScoreRequest's settings") {
    const ScoreRequest q;
    check_defaults("score", {{"metrics", text(q.metrics)},
                             {"scenes", text(q.scenes)},
                             {"snr_db", "20,30,40"},  // ScoreRequest::kDefaultSnrDb, as text
                             {"wiener_nsr", q.wiener_nsr},
                             {"tv_lambda", q.tv_lambda},
                             {"tv_iterations", text(q.tv_iterations)},
                             {"noise_seeds", text(q.noise_seeds)},
                             {"seed", text(static_cast<double>(q.seed))},
                             {"prior", prior_kind_name(q.prior.kind)},
                             {"prior.count", text(q.prior.count)}});
}

TEST_CASE("compare's flags default to CompareRequest's settings") {
    const CompareRequest q;
    REQUIRE(CompareRequest::kDefaultSnrDb == std::vector<double>{30.0});
    REQUIRE(ScoreRequest::kDefaultSnrDb == std::vector<double>{20.0, 30.0, 40.0});
    check_defaults("compare", {{"scenes", text(q.scenes)},
                               {"snr_db", "30"},
                               {"wiener_nsr", q.wiener_nsr},
                               {"tv_lambda", q.tv_lambda},
                               {"tv_iterations", text(q.tv_iterations)},
                               {"seed", text(static_cast<double>(q.seed))},
                               {"baseline_count", text(q.baseline_count)},
                               {"prior", prior_kind_name(q.prior.kind)},
                               {"prior.count", text(q.prior.count)}});
}

TEST_CASE("export's flags default to ExportRequest's settings") {
    const ExportRequest q;
    check_defaults("export", {{"vendor", q.vendor},
                              {"shape", q.shape},
                              {"chord_tol", q.chord_tol},
                              {"margin", q.margin},
                              {"hierarchy", q.hierarchy},
                              {"layer", text(q.layer)},
                              {"datatype", text(q.datatype)},
                              {"dxf_layer", q.dxf_layer}});
}

TEST_CASE("calibrate's flags default to CalibrateRequest's settings") {
    const CalibrateRequest q;
    check_defaults("calibrate", {{"max_rotation_deg", text(q.options.max_rotation_deg)},
                                 {"pitch_range", text(q.options.pitch_range)},
                                 {"threshold_sigmas", text(q.options.threshold_sigmas)}});
}

TEST_CASE("depthmap's flags default to DepthmapRequest's settings") {
    const DepthmapRequest q;
    // steps unset: chosen from the camera (one resolvable step apart); --help shows no number.
    REQUIRE_FALSE(q.steps.has_value());
    check_defaults("depthmap", {{"steps", ""},
                                {"smooth", text(q.smooth)},
                                {"wiener_nsr", text(q.wiener_nsr)},
                                {"cost_window", text(q.window)}});
}

TEST_CASE("decode's flags default to DecodeRequest's settings") {
    const DecodeRequest q;
    // A setting read from the capture unless given ("auto") shows as auto.
    auto or_auto = [](bool automatic, const std::string& value) {
        return automatic ? std::string("auto") : value;
    };
    check_defaults("decode", {{"method", or_auto(q.method_auto, decode_method_name(q.method))},
                              {"model", or_auto(q.model_auto, conv_model_name(q.model))},
                              {"crop", or_auto(q.crop_auto, "center")},
                              {"nsr", or_auto(q.nsr_auto, text(q.nsr))},
                              {"lambda", or_auto(q.lambda_auto, text(q.lambda))},
                              {"regulariser", regulariser_name(q.regulariser)},
                              {"iterations", text(q.iterations)},
                              {"tolerance", text(q.tolerance)},
                              {"downsample", text(q.downsample)},
                              {"background", background_mode_name(q.background.mode)},
                              {"normalize", normalize_mode_name(q.normalize)},
                              {"precision", precision_name(q.precision)},
                              {"threads", text(q.threads)}});
}
