// Design sweeps: sweep() is `pinmask sweep` with Python's keywords: one search() per design
// point, the points a grid (the Cartesian product over the keys in alphabetical order, the last
// varying fastest; the sweep file's "grid", named product here because grid is search()'s pattern
// size) or a list, each point the base keywords with its own values. The command's
// rules: every point has an evaluation budget (evals >= 1: points are reproducible), threads
// default to 1 per point, at most io::kMaxSweepPoints points, and every key is checked before any
// search starts. The rows carry the keys of `pinmask sweep --json`'s rows.
#include <string>
#include <vector>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "io/sweep_config.hpp"
#include "python/common.hpp"
#include "python/result.hpp"

namespace pinmask::python {

namespace {

// search()'s keyword names, from pybind11's signature line (the first docstring line).
std::vector<std::string> search_keywords(const py::object& search) {
    const std::string doc = py::str(search.attr("__doc__"));
    const std::string first = doc.substr(0, doc.find('\n'));
    std::vector<std::string> names;
    const py::list found = py::module_::import("re").attr("findall")(R"((?:\(|, )(\w+): )", first);
    for (const py::handle& h : found) names.push_back(h.cast<std::string>());
    return names;
}

// A value as the row shows it: numbers, strings, booleans and None as they are, anything else
// (a Camera, a list) by its repr.
py::object row_value(const py::handle& v) {
    if (v.is_none() || py::isinstance<py::bool_>(v) || py::isinstance<py::int_>(v) ||
        py::isinstance<py::float_>(v) || py::isinstance<py::str>(v))
        return py::reinterpret_borrow<py::object>(v);
    return py::repr(v);
}

}  // namespace

void bind_sweep(py::module_& m) {
    m.def(
        "sweep",
        [](const py::object& product, const py::object& points, const py::object& progress,
           const py::kwargs& base) {
            const py::object search = py::module_::import("pinmask").attr("search");
            const std::vector<std::string> known = search_keywords(search);
            const auto check_key = [&](const std::string& key, const std::string& where) {
                if (key == "progress")
                    throw invalid_field(where, key, "is sweep()'s own progress, not per point");
                if (std::find(known.begin(), known.end(), key) == known.end())
                    throw invalid_field(where, key, "is not a keyword of search()");
            };
            for (auto item : base) check_key(py::str(item.first), "base keyword");
            if (product.is_none() == points.is_none())
                throw InvalidInput("sweep needs exactly one of " + field_ref("product") + " and " +
                                   field_ref("points"));
            // The points as (keys, values) pairs, in the command's order.
            std::vector<std::string> keys;
            std::vector<py::dict> chosen;
            if (!product.is_none()) {
                const py::dict g = product.cast<py::dict>();
                if (g.empty())
                    throw invalid_field(field_ref("product"), "{}", "vary at least one key");
                std::vector<std::pair<std::string, py::list>> axes;
                for (auto item : g) {
                    const std::string key = py::str(item.first);
                    check_key(key, "product key");
                    py::list values = py::list(py::reinterpret_borrow<py::object>(item.second));
                    if (py::isinstance<py::str>(item.second) || values.empty())
                        throw invalid_field("product." + key, std::string(py::repr(item.second)),
                                            "must be a non-empty list of values");
                    axes.emplace_back(key, values);
                }
                std::sort(axes.begin(), axes.end(),
                          [](const auto& a, const auto& b) { return a.first < b.first; });
                std::size_t count = 1;
                for (const auto& [key, values] : axes) {
                    keys.push_back(key);
                    count *= values.size();
                    if (count > io::kMaxSweepPoints)
                        throw invalid_field(field_ref("product"),
                                            std::to_string(count) + "+ points",
                                            "at most " + std::to_string(io::kMaxSweepPoints) +
                                                " points (each is a whole search)");
                }
                for (std::size_t i = 0; i < count; ++i) {
                    py::dict p;
                    std::size_t rest = i;
                    for (std::size_t a = axes.size(); a-- > 0;) {
                        const py::list& values = axes[a].second;
                        p[py::str(axes[a].first)] = values[rest % values.size()];
                        rest /= values.size();
                    }
                    chosen.push_back(p);
                }
            } else {
                const py::list list = py::list(points);
                if (list.empty())
                    throw invalid_field(field_ref("points"), "[]", "give at least one point");
                if (list.size() > io::kMaxSweepPoints)
                    throw invalid_field(field_ref("points"), std::to_string(list.size()),
                                        "at most " + std::to_string(io::kMaxSweepPoints) +
                                            " points (each is a whole search)");
                std::vector<std::string> seen;
                for (const py::handle& h : list) {
                    const py::dict p = h.cast<py::dict>();
                    for (auto item : p) {
                        const std::string key = py::str(item.first);
                        check_key(key, "point key");
                        if (std::find(seen.begin(), seen.end(), key) == seen.end())
                            seen.push_back(key);
                    }
                    chosen.push_back(p);
                }
                std::sort(seen.begin(), seen.end());
                keys = seen;
            }
            // Every point's keywords, checked before any search starts.
            std::vector<py::dict> calls;
            for (std::size_t i = 0; i < chosen.size(); ++i) {
                py::dict kw;
                for (auto item : base) kw[item.first] = item.second;
                for (auto item : chosen[i]) kw[item.first] = item.second;
                if (!kw.contains("threads")) kw["threads"] = 1;
                const bool budget = kw.contains("evals") && !kw["evals"].is_none() &&
                                    kw["evals"].cast<long long>() >= 1;
                if (!budget)
                    throw invalid_field(
                        "point " + std::to_string(i) + " " + field_ref("evals"),
                        kw.contains("evals") ? std::string(py::repr(kw["evals"])) : "unset",
                        "every point needs an evaluation budget >= 1 (a sweep's "
                        "points are reproducible, never searched for a time)");
                if (kw["threads"].cast<long long>() == 0)
                    throw invalid_field("point " + std::to_string(i) + " " + field_ref("threads"),
                                        "0", "must be >= 1 (0, all cores, depends on the machine)");
                calls.push_back(kw);
            }
            py::list rows, masks;
            for (std::size_t i = 0; i < calls.size(); ++i) {
                py::dict r;
                try {
                    r = search(**calls[i]).cast<py::dict>();
                } catch (py::error_already_set& e) {
                    std::string label;
                    for (auto item : chosen[i])
                        label += (label.empty() ? "" : ", ") + std::string(py::str(item.first)) +
                                 " = " + std::string(py::repr(item.second));
                    const std::string what = py::str(e.value());
                    const std::string text =
                        "sweep point " + std::to_string(i) + " (" + label + "): " + what;
                    if (e.matches(PyExc_ValueError)) throw InvalidInput(text);
                    if (e.matches(PyExc_RuntimeError)) throw RuntimeFailure(text);
                    throw;
                }
                const py::list ranked = r["ranked"];
                if (ranked.empty())
                    throw RuntimeFailure("sweep point " + std::to_string(i) +
                                         ": the search returned no candidate");
                const py::dict best = ranked[0].cast<py::dict>();
                py::dict row;
                row["point"] = i;
                for (const std::string& key : keys) {
                    const py::str k(key);
                    row[k] = chosen[i].contains(k)  ? row_value(chosen[i][k])
                             : calls[i].contains(k) ? row_value(calls[i][k])
                                                    : py::object(py::none());
                }
                row["objective"] = best["objective"];
                row["evaluations"] = r["evaluations"];
                row["geometry_hash"] = best["geometry_hash"];
                // The best mask's terms and figures: its ranked row (search --json's) without
                // the ranking's own columns.
                for (auto item : best) {
                    const std::string k = py::str(item.first);
                    if (k != "rank" && k != "path" && k != "geometry_hash" && k != "objective" &&
                        k != "reranked" && k != "upper_bound_analytic_mmse_psnr_db")
                        row[item.first] = item.second;
                }
                rows.append(row);
                masks.append(r["masks"].cast<py::list>()[0]);
                if (!progress.is_none()) {
                    py::dict info;
                    info["point"] = i;
                    info["done"] = i + 1;
                    info["count"] = calls.size();
                    if (progress(info).is(py::bool_(false))) break;
                }
            }
            py::dict d;
            d["keys"] = keys;
            d["points"] = rows.size();
            d["rows"] = rows;
            d["masks"] = masks;
            return as_result(d);
        },
        py::kw_only(), py::arg("product") = py::none(), py::arg("points") = py::none(),
        py::arg("progress") = py::none(),
        R"(A design sweep, as `pinmask sweep`: one search() per design point.
product: {keyword: [values]} (the sweep file's "grid": the Cartesian product, keys in
alphabetical order, the last varying fastest), or points: [{keyword: value, ...}, ...]; every other keyword is search()'s base
setting for every point (holes, grid, camera, evals, photons, ...). Any search() keyword may
vary, a Camera included (product={"camera": [cam_a, cam_b]}). The command's rules: every point
needs evals >= 1 (points are reproducible), threads default to 1 per point (0 refused), at most
10000 points, and every key is checked before any search starts (ValueError naming it).
progress: called after each point with {point, done, count}; return False to stop (the rows so
far are returned). Returns {keys (the varied keywords, sorted), points, rows: [{point, each
varied keyword's value (None where the point leaves it at search()'s default), objective, evaluations, geometry_hash, and the best mask's scores}]
(the rows of `pinmask sweep --json`), masks (the best Mask of each point)}.)");
}

}  // namespace pinmask::python
