#include "io/search_config.hpp"

#include <limits>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/units.hpp"
#include "design/psf/kernel_model.hpp"
#include "io/json_strict.hpp"
#include "io/optics_json.hpp"

namespace pinmask::io {
namespace {

using namespace json_strict;

// A configuration file is a few hundred bytes; anything this large is not one.
constexpr std::uintmax_t kMaxConfigBytes = 1 << 20;

std::string one_of(const Json& j, const std::string& path, std::initializer_list<const char*> ok) {
    const std::string s = read_string(j, path);
    std::string list;
    for (const char* o : ok) {
        if (s == o) return s;
        list += list.empty() ? o : std::string(" | ") + o;
    }
    fail(path, "'" + s + "' is not one of " + list);
}

int int_at_least(const Json& j, const std::string& path, int lo) {
    const int v = read_int(j, path);
    if (v < lo) fail(path, std::to_string(v) + " must be >= " + std::to_string(lo));
    return v;
}

// An array of strings; `what` names the elements in the message ("paths", "scene names").
std::vector<std::string> read_strings(const Json& v, const std::string& p, const char* what) {
    if (!v.is_array())
        fail(p, std::string("must be an array of ") + what + ", got " + v.type_name());
    std::vector<std::string> out;
    for (std::size_t i = 0; i < v.size(); ++i) out.push_back(read_string(v[i], indexed(p, i)));
    return out;
}

template <class T, class Read>
void read_into(const ObjectReader& r, const char* key, std::optional<T>& out, Read read) {
    if (const Json* v = r.optional(key)) out = read(*v, r.path(key));
}

}  // namespace

SearchConfig parse_search_config(const std::string& text) {
    Json j;
    try {
        j = parse_strict(text);
    } catch (const nlohmann::json::exception& e) {
        throw InvalidInput(std::string("invalid JSON: ") + json_error_words(e));
    }
    ObjectReader r(j, "",
                   {"format",
                    "version",
                    "generator",
                    "strategy",
                    "time",
                    "evaluations_per_chain",
                    "threads",
                    "seed",
                    "top",
                    "grid",
                    "holes",
                    "max_holes",
                    "tiles",
                    "min_spacing_cells",
                    "keep_out",
                    "pixels_per_cell",
                    "kernel_requested",
                    "kernel_resolved",
                    "kernel_path",
                    "noise",
                    "filter",
                    "prior",
                    "weights",
                    "depth_range",
                    "rerank_scenes",
                    "rerank_tv",
                    "allow_spectral_zeros",
                    "rank_by",
                    "objective",
                    "robust",
                    "optics",
                    "ranks"});
    if (read_string(r.required("format"), "format") != kSearchConfigFormat)
        fail("format",
             "must be \"" + std::string(kSearchConfigFormat) + "\" (not a search config)");
    if (const int v = read_int(r.required("version"), "version"); v != kSearchConfigVersion)
        fail("version", std::to_string(v) + " is not supported (this pinmask reads version " +
                            std::to_string(kSearchConfigVersion) + ")");
    r.reject_unknown();
    if (const Json* g = r.optional("generator")) read_string(*g, "generator");
    if (const Json* k = r.optional("kernel_resolved")) read_string(*k, "kernel_resolved");

    SearchConfig c;
    read_into(r, "strategy", c.strategy, [](const Json& v, const std::string& p) {
        return one_of(v, p, {"random", "anneal"});
    });
    // "time": null is what an --evals run records (it had no time budget).
    if (const Json* t = r.optional("time"); !(t && t->is_null()))
        read_into(r, "time", c.time, [](const Json& v, const std::string& p) {
            const std::string s = read_string(v, p);
            const double seconds = parse_duration_s(s, p);
            if (!(seconds > 0)) fail(p, "'" + s + "' must be a positive duration");
            return s;
        });
    read_into(r, "evaluations_per_chain", c.evaluations_per_chain,
              [](const Json& v, const std::string& p) -> std::int64_t {
                  if (!v.is_number_integer() ||
                      (v.is_number_unsigned() && v.get<std::uint64_t>() > std::uint64_t(INT64_MAX)))
                      fail(p, "must be an integer >= 0, got " + v.dump());
                  const auto e = v.get<std::int64_t>();
                  if (e < 0) fail(p, "must be an integer >= 0, got " + v.dump());
                  return e;
              });
    read_into(r, "ranks", c.ranks,
              [](const Json& v, const std::string& p) { return int_at_least(v, p, 1); });
    read_into(r, "threads", c.threads,
              [](const Json& v, const std::string& p) { return int_at_least(v, p, 0); });
    read_into(r, "seed", c.seed, [](const Json& v, const std::string& p) {
        if (!v.is_number_unsigned()) fail(p, "must be an integer >= 0, got " + v.dump());
        return v.get<std::uint64_t>();
    });
    for (auto [key, field] :
         {std::pair{"top", &c.top}, std::pair{"grid", &c.grid}, std::pair{"holes", &c.holes},
          std::pair{"tiles", &c.tiles}, std::pair{"pixels_per_cell", &c.pixels_per_cell}}) {
        read_into(r, key, *field,
                  [](const Json& v, const std::string& p) { return int_at_least(v, p, 1); });
    }
    read_into(r, "max_holes", c.max_holes,
              [](const Json& v, const std::string& p) { return int_at_least(v, p, 0); });
    read_into(r, "min_spacing_cells", c.min_spacing_cells, [](const Json& v, const std::string& p) {
        const double s = read_number(v, p);
        if (!(s > 0)) fail(p, "must be > 0");
        return s;
    });
    read_into(r, "keep_out", c.keep_out, [](const Json& v, const std::string& p) {
        return one_of(v, p, {"none", "border"});
    });
    read_into(r, "kernel_requested", c.kernel, [](const Json& v, const std::string& p) {
        const std::string name = read_string(v, p);
        parse_kernel_model(name, p);  // design/psf/kernel_model names the models
        return name;
    });
    read_into(r, "kernel_path", c.kernel_path, read_string);
    read_into(r, "filter", c.filter, read_string);
    if (const Json* noise = r.optional("noise")) {
        ObjectReader n(*noise, "noise",
                       {"model", "snr_db", "photons_per_pinhole", "read_noise_e", "dark_current_e",
                        "full_well_e", "adc_bits", "film_optical_density"});
        n.reject_unknown();
        std::string model = "gaussian";
        if (const Json* m = n.optional("model"))
            model = one_of(*m, n.path("model"), {"gaussian", "photon"});
        read_into(n, "snr_db", c.snr_db, read_number);
        const auto number_or_inf = [](const Json& v, const std::string& p) {
            return v.is_null() ? std::numeric_limits<double>::infinity() : read_number(v, p);
        };
        read_into(n, "photons_per_pinhole", c.photons, read_number);
        read_into(n, "read_noise_e", c.read_noise, read_number);
        read_into(n, "dark_current_e", c.dark_current, read_number);
        read_into(n, "full_well_e", c.full_well, number_or_inf);
        read_into(n, "film_optical_density", c.optical_density, number_or_inf);
        read_into(n, "adc_bits", c.bits,
                  [](const Json& v, const std::string& p) { return int_at_least(v, p, 0); });
        if (model == "photon" && !c.photons)
            fail(n.path("photons_per_pinhole"), "is required for the photon model");
        if (model == "gaussian" && c.photons)
            fail(n.path("photons_per_pinhole"), "belongs to the photon model");
    }
    if (const Json* prior = r.optional("prior")) {
        ObjectReader n(*prior, "prior", {"family", "scenes", "files"});
        n.reject_unknown();
        read_into(n, "family", c.prior_family, [](const Json& v, const std::string& p) {
            return one_of(v, p, {"natural", "text", "stars", "files"});
        });
        read_into(n, "files", c.prior_files,
                  [](const Json& v, const std::string& p) { return read_strings(v, p, "paths"); });
        read_into(n, "scenes", c.prior_scenes,
                  [](const Json& v, const std::string& p) { return int_at_least(v, p, 1); });
    }
    if (const Json* weights = r.optional("weights")) {
        ObjectReader w(
            *weights, "weights",
            {"analytic_wiener", "max_sidelobe", "sidelobe_energy", "min_spectrum", "depth"});
        w.reject_unknown();
        read_into(w, "analytic_wiener", c.w_analytic, read_number);
        read_into(w, "max_sidelobe", c.w_max_sidelobe, read_number);
        read_into(w, "sidelobe_energy", c.w_sidelobe_energy, read_number);
        read_into(w, "min_spectrum", c.w_min_spectrum, read_number);
        read_into(w, "depth", c.w_depth, read_number);
    }
    if (const Json* range = r.optional("depth_range")) {
        ObjectReader d(*range, "depth_range", {"from_m", "to_m"});
        d.reject_unknown();
        read_into(d, "from_m", c.depth_from, read_number);
        read_into(d, "to_m", c.depth_to, read_number);
    }
    read_into(r, "rerank_scenes", c.rerank_scenes, [](const Json& v, const std::string& p) {
        return read_strings(v, p, "scene names");
    });
    read_into(r, "rerank_tv", c.rerank_tv, read_bool);
    read_into(r, "allow_spectral_zeros", c.allow_spectral_zeros, read_bool);
    read_into(r, "rank_by", c.rank_by, [](const Json& v, const std::string& p) {
        return one_of(v, p, {"wiener", "tv"});
    });
    read_into(r, "objective", c.objective, [](const Json& v, const std::string& p) {
        return one_of(v, p, {"nominal", "robust"});
    });
    read_into(r, "robust", c.robust, read_string);
    if (const Json* optics = r.optional("optics")) c.optics = optics_from_json(*optics);
    return c;
}

SearchConfig read_search_config(const std::filesystem::path& path) {
    return parse_bounded_file(path, field_ref("config"), kMaxConfigBytes, "a search configuration",
                              parse_search_config);
}

}  // namespace pinmask::io
