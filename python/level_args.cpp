#include "python/level_args.hpp"

#include <sstream>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"

namespace pinmask::python {
namespace {

// A number or a sequence of numbers; InvalidInput naming `field` otherwise.
std::vector<double> number_list(const py::object& v, const std::string& field) {
    const auto bad = [&] {
        return invalid_field(field, py::repr(v).cast<std::string>(),
                             "expected a number or a list of numbers");
    };
    if (py::isinstance<py::bool_>(v) || py::isinstance<py::str>(v)) throw bad();
    if (py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v)) return {v.cast<double>()};
    if (!py::isinstance<py::sequence>(v)) throw bad();
    std::vector<double> out;
    for (const py::handle& item : v.cast<py::sequence>()) {
        if (py::isinstance<py::bool_>(item) ||
            !(py::isinstance<py::float_>(item) || py::isinstance<py::int_>(item)))
            throw bad();
        out.push_back(item.cast<double>());
    }
    return out;
}

std::string number_text(const std::vector<double>& values) {
    std::ostringstream s;
    for (std::size_t i = 0; i < values.size(); ++i) s << (i ? "," : "") << values[i];
    return s.str();
}

}  // namespace

std::vector<NoiseLevel> noise_levels_arg(const py::object& snr_db, const py::object& photons,
                                         const SensorSettings& sensor,
                                         const std::vector<double>& default_snr_db,
                                         std::string* text) {
    NoiseLevelSettings s;
    s.sensor = sensor;
    if (!photons.is_none()) {
        if (!snr_db.is_none()) {
            throw invalid_field(field_ref("snr_db"),
                                number_text(number_list(snr_db, field_ref("snr_db"))),
                                "cannot be combined with " + field_ref("photons"));
        }
        s.photons = number_list(photons, field_ref("photons"));
        if (s.photons.empty())
            throw invalid_field(field_ref("photons"), "''", "needs at least one item");
    } else {
        s.snr_db = snr_db.is_none() ? default_snr_db : number_list(snr_db, field_ref("snr_db"));
    }
    return noise_levels(s, text);
}

PriorSpec prior_arg(const py::object& prior, int prior_scenes) {
    if (py::isinstance<py::str>(prior) || py::hasattr(prior, "__fspath__"))
        return parse_prior_spec(py::str(prior).cast<std::string>(), prior_scenes);
    if (!py::isinstance<py::sequence>(prior)) {
        throw invalid_field(field_ref("prior"), py::repr(prior).cast<std::string>(),
                            "expected natural, text, stars or image files");
    }
    std::string files;
    for (const py::handle& item : prior.cast<py::sequence>()) {
        const std::string path = py::str(item).cast<std::string>();
        files += (files.empty() ? "" : ",") + path;
    }
    return parse_prior_spec(files, prior_scenes);
}

}  // namespace pinmask::python
