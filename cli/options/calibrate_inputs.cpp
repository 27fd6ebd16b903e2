#include "cli/options/calibrate_inputs.hpp"

#include <exception>
#include <iostream>

#include "cli/options/flag_names.hpp"
#include "core/errors/error.hpp"
#include "core/image/image_io.hpp"

namespace pinmask::cli {

void apply_saturation_flag(const std::string& text, calibrate::CalibrationOptions& options) {
    // auto: an integer file's largest count, or a flat top found in a float capture; a value or
    // none is the user's word.
    options.detect_saturation = text == "auto";
    if (text != "auto" && text != "none") {
        try {
            options.saturation_level = std::stod(text);
        } catch (const std::exception&) {
            throw invalid_field("--saturation", text, "must be auto, none or a count");
        }
    }
}

Plane read_grey(const std::string& path, const std::string& what, BayerMode bayer,
                double* full_scale, RawInfo& raw) {
    LoadedImage img = read_capture(path, bayer, &raw);
    if (!raw.note.empty())
        std::cerr << "calibrate: " << path << ": " << spell_flags(raw.note) << "\n";
    if (full_scale) *full_scale = img.full_scale;
    Plane p = img.image.channels.at(0);
    for (std::size_t c = 1; c < img.image.channels.size(); ++c) p += img.image.channels[c];
    if (!is_all_finite(p)) throw InvalidInput(what + " '" + path + "' holds NaN or Inf");
    return p;
}

}  // namespace pinmask::cli
