#include "io/psf_stack.hpp"

#include <cmath>
#include <set>
#include <string>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/image/image_io.hpp"
#include "core/limits/resource_limits.hpp"
#include "core/units/number_format.hpp"
#include "io/json_strict.hpp"

namespace pinmask::io {
namespace {

namespace fs = std::filesystem;
using namespace json_strict;

constexpr std::uintmax_t kMaxStackBytes = 1u << 20;
constexpr std::size_t kMinPlanes = 2, kMaxPlanes = 1000;

struct Listing {
    std::vector<double> distances_m;
    std::vector<std::string> files;
};

Listing parse_listing(const std::string& text) {
    Json j;
    try {
        j = parse_strict(text);
    } catch (const nlohmann::json::exception& e) {
        throw InvalidInput(std::string("invalid JSON: ") + json_error_words(e));
    }
    ObjectReader r(j, "", {"format", "version", "planes"});
    if (read_string(r.required("format"), "format") != kPsfStackFormat)
        fail("format", "must be \"" + std::string(kPsfStackFormat) + "\" (not a PSF stack)");
    if (const int v = read_int(r.required("version"), "version"); v != kPsfStackVersion)
        fail("version", std::to_string(v) + " is not supported (this pinmask reads version " +
                            std::to_string(kPsfStackVersion) + ")");
    r.reject_unknown();
    const Json& planes = r.required("planes");
    if (!planes.is_array())
        fail("planes", std::string("must be a list, got ") + planes.type_name());
    if (planes.size() < kMinPlanes || planes.size() > kMaxPlanes)
        fail("planes", std::to_string(planes.size()) + " planes: need between " +
                           std::to_string(kMinPlanes) + " and " + std::to_string(kMaxPlanes));
    Listing out;
    std::set<double> seen;
    for (std::size_t k = 0; k < planes.size(); ++k) {
        const std::string path = indexed("planes", k);
        ObjectReader p(planes[k], path, {"object_distance_m", "psf"});
        p.reject_unknown();
        const double u = read_number(p.required("object_distance_m"), p.path("object_distance_m"));
        if (!(u > 0.0))
            fail(p.path("object_distance_m"), format_number(u) + ": must be > 0 (metres)");
        if (!seen.insert(u).second)
            fail(p.path("object_distance_m"),
                 format_number(u) + ": the same distance as an earlier plane");
        const std::string file = read_string(p.required("psf"), p.path("psf"));
        if (file.empty()) fail(p.path("psf"), "empty path");
        out.distances_m.push_back(u);
        out.files.push_back(file);
    }
    return out;
}

}  // namespace

PsfStack read_psf_stack(const fs::path& file_or_dir) {
    std::error_code ec;
    const fs::path file =
        fs::is_directory(file_or_dir, ec) ? file_or_dir / "psf_stack.json" : file_or_dir;
    const Listing listing = parse_bounded_file(file, field_ref("psf_stack"), kMaxStackBytes,
                                               "a PSF stack", parse_listing);
    const fs::path base = file.parent_path();
    PsfStack out;
    out.files.push_back(file);
    double bytes = 0.0;
    for (std::size_t k = 0; k < listing.files.size(); ++k) {
        const fs::path psf_path = fs::path(listing.files[k]).is_absolute()
                                      ? fs::path(listing.files[k])
                                      : base / listing.files[k];
        const std::string where = field_ref("psf_stack") + " " + file.string() + ": plane " +
                                  std::to_string(k) + " (" + psf_path.string() + ")";
        LoadedImage im;
        try {
            im = read_image(psf_path);
        } catch (const InvalidInput& e) {
            throw InvalidInput(where + ": " + e.what());
        }
        if (im.image.n_channels() != 1)
            throw InvalidInput(where + ": " + std::to_string(im.image.n_channels()) +
                               " channels; a PSF has one");
        Plane& h = im.image.channels[0];
        if (!out.psfs.empty() && (h.rows() != out.psfs[0].rows() || h.cols() != out.psfs[0].cols()))
            throw InvalidInput(where + ": " + std::to_string(h.rows()) + "x" +
                               std::to_string(h.cols()) + " differs from plane 0's " +
                               std::to_string(out.psfs[0].rows()) + "x" +
                               std::to_string(out.psfs[0].cols()));
        if (!is_all_finite(h)) throw InvalidInput(where + ": holds NaN or Inf");
        if (h.minCoeff() < 0.0) throw InvalidInput(where + ": holds negative values");
        if (!(h.sum() > 0.0)) throw InvalidInput(where + ": holds no light (sum 0)");
        bytes += double(h.size()) * 8.0;
        check_memory(bytes, "the PSF stack's " + std::to_string(k + 1) + " planes");
        out.distances_m.push_back(listing.distances_m[k]);
        out.psfs.push_back(std::move(h));
        out.files.push_back(psf_path);
    }
    return out;
}

}  // namespace pinmask::io
