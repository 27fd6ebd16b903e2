#include "cli/options/camera_options.hpp"

#include <cmath>
#include <iostream>
#include <string>
#include <utility>

#include "cli/options/flag_names.hpp"
#include "core/errors/error.hpp"
#include "core/units/units.hpp"
#include "design/optics/default_pinhole.hpp"
#include "design/optics/design_run.hpp"
#include "design/optics/working_distance.hpp"
#include "design/pattern/pattern.hpp"
#include "io/camera_json.hpp"

namespace pinmask::cli {

void add_camera_options(CLI::App& cmd, CameraOptions& o) {
    cmd.add_option("--camera", o.camera_file,
                   "Camera file (*.camera.json, e.g. from design --save-camera) used instead of "
                   "the preset; camera flags given beside it override its values");
    cmd.add_option_function<std::string>(
           "--preset",
           [&o](const std::string& name) {
               o.preset = name;
               o.preset_given = true;
           },
           "Camera preset: paper (u 6m, f' 120mm, f 55mm, d 440um, w 30um, 720x480, 550nm); "
           "given, its pinhole is kept when other optics flags change the camera")
        ->check(CLI::IsMember({"paper"}))
        ->default_str("paper");
    cmd.add_option("--lens-focal", o.lens_focal,
                   "Lens focal length f' (e.g. 120mm; inf = no lens)");
    cmd.add_option("--sensor-distance", o.sensor_distance, "Lens-to-sensor distance f (e.g. 55mm)");
    cmd.add_option("--object-distance", o.object_distance, "Object distance u (e.g. 6m, or inf)");
    cmd.add_option("--wavelength", o.wavelength,
                   "Design wavelength, the centre of the band (e.g. 550nm)");
    cmd.add_option("--bandwidth", o.bandwidth,
                   "Full width at half maximum of the light's spectrum (e.g. 30nm for an LED; "
                   "default 0 = one wavelength, at most half the wavelength): the kernels sum a "
                   "Gaussian band sampled at 13 wavelengths over +-1.5 FWHM (docs/commands.md)");
    cmd.add_option("--pixel-pitch", o.pixel_pitch, "Sensor pixel pitch w (e.g. 30um)");
    cmd.add_option("--pinhole", o.pinhole,
                   "Pinhole side d = cell side (e.g. 440um). Default: the preset's 440um; for "
                   "other optics (--lens-focal, --sensor-distance, --wavelength or --pixel-pitch "
                   "given, without --preset or --camera) the pinhole for whole pixels per cell "
                   "nearest the diffraction optimum 1.56 sqrt(lambda |z_eff(u)|), said on stderr");
    cmd.add_option("--sensor", o.sensor, "Sensor size in pixels, WIDTHxHEIGHT (e.g. 720x480)");
}

Camera resolve_camera(const CameraOptions& o) {
    Camera c = o.camera_file ? io::read_camera_file(*o.camera_file)
                             : (o.base ? *o.base : paper_camera());  // paper: the only preset
    if (o.lens_focal)
        c.lens_focal_m = parse_length_m(*o.lens_focal, "--lens-focal", AllowInfinity::kYes);
    if (o.sensor_distance)
        c.sensor_distance_m = parse_length_m(*o.sensor_distance, "--sensor-distance");
    if (o.object_distance) {
        c.object_distance_m =
            parse_length_m(*o.object_distance, "--object-distance", AllowInfinity::kYes);
    }
    if (o.wavelength) c.wavelength_m = parse_length_m(*o.wavelength, "--wavelength");
    if (o.bandwidth) c.bandwidth_m = parse_length_m(*o.bandwidth, "--bandwidth");
    if (o.pixel_pitch) c.pixel_pitch_m = parse_length_m(*o.pixel_pitch, "--pixel-pitch");
    if (o.pinhole) c.pinhole_m = parse_length_m(*o.pinhole, "--pinhole");
    if (o.sensor) {
        const Size2 s = parse_size(*o.sensor, "--sensor");
        c.sensor_cols = s.cols;
        c.sensor_rows = s.rows;
    }
    // design/optics/camera names Camera fields; on the command line the flag is what the user
    // typed.
    static const std::pair<const char*, const char*> kFlagOf[] = {
        {"object_distance_m", "--object-distance"},
        {"lens_focal_m", "--lens-focal"},
        {"sensor_distance_m", "--sensor-distance"},
        {"wavelength_m", "--wavelength"},
        {"bandwidth_m", "--bandwidth"},
        {"pixel_pitch_m", "--pixel-pitch"},
        {"pinhole_m", "--pinhole"},
        {"sensor", "--sensor"}};
    const auto validated = [&](const Camera& cam) {
        try {
            validate(cam);
        } catch (const InvalidInput& e) {
            const std::string what = e.what();
            for (const auto& [field, flag] : kFlagOf) {
                if (what.rfind(std::string(field) + " ", 0) == 0) {
                    throw InvalidInput(std::string(flag) + ": " + what);
                }
            }
            throw;
        }
    };
    validated(c);
    if (pinhole_defaulted(o)) {
        const DefaultPinhole chosen = default_pinhole(c);
        c.pinhole_m = chosen.pinhole_m;
        validated(c);
        std::cerr << "pinmask: note: " << spell_flags(chosen.note) << "\n";
    }
    // Cells under half a pixel would be silently modelled as 1 px: said for every command that
    // builds its camera here (design, generate, search, calibrate), with the flags spelled.
    if (auto why = sub_pixel_cells(c)) {
        for (const auto& [field, flag] : kFlagOf) {
            if (std::string_view(field) == "sensor") continue;  // not named; a prefix of others
            for (auto at = why->find(field); at != std::string::npos; at = why->find(field, at))
                why->replace(at, std::string(field).size(), flag);
        }
        std::cerr << "pinmask: warning: " << *why << "\n";
    }
    return c;
}

bool pinhole_defaulted(const CameraOptions& o) {
    return o.default_pinhole && !o.preset_given && !o.camera_file && !o.base && !o.pinhole &&
           (o.lens_focal || o.sensor_distance || o.wavelength || o.pixel_pitch);
}

std::vector<CameraInput> camera_inputs(const CameraOptions& o, const Camera& c) {
    const std::string base =
        o.camera_file ? "camera file" : (o.base ? "config" : "paper preset default");
    auto from = [&](const std::optional<std::string>& flag) { return flag ? "flag" : base; };
    const auto* sym = kCameraInputSymbols;  // the design report's order
    return {
        {sym[0], format_length(c.pinhole_m),
         pinhole_defaulted(o) ? "whole-pixel optimum (no --pinhole given)" : from(o.pinhole)},
        {sym[1], format_length(c.wavelength_m), from(o.wavelength)},
        {sym[2], c.bandwidth_m == 0.0 ? "0 (one wavelength)" : format_length(c.bandwidth_m),
         from(o.bandwidth)},
        {sym[3], format_length(c.sensor_distance_m), from(o.sensor_distance)},
        {sym[4], format_length(c.lens_focal_m), from(o.lens_focal)},
        {sym[5], format_length(c.object_distance_m), from(o.object_distance)},
        {sym[6], format_length(c.pixel_pitch_m), from(o.pixel_pitch)},
        {sym[7], std::to_string(c.sensor_cols) + " x " + std::to_string(c.sensor_rows) + " px",
         from(o.sensor)},
    };
}

void add_geometry_options(CLI::App& cmd, GeometryOptions& o, std::string* holes_range) {
    cmd.add_option("--grid", o.grid, "Pattern size n (n x n cells, 1..4096)")
        ->capture_default_str();
    if (holes_range) {
        cmd.add_option("--holes", *holes_range,
                       "Number of pinholes K, or a range A..B: the search adds and removes "
                       "pinholes, keeps the best mask per K and plots predicted PSNR against K")
            ->capture_default_str();
    } else {
        cmd.add_option("--holes", o.holes, "Number of pinholes K")->capture_default_str();
    }
    cmd.add_option("--tiles", o.tiles, "Tiles per side of the cyclic mask")->capture_default_str();
    cmd.add_option("--spacing", o.spacing,
                   "Minimum pinhole centre spacing in cells, on the torus (2 = no two pinholes in "
                   "each other's 8-neighbourhood)")
        ->capture_default_str();
}

PatternGeometry resolve_geometry(const GeometryOptions& g) {
    const PatternGeometry geometry{g.grid, g.holes, g.tiles, g.tiles};
    validate(geometry);  // design/optics/optics: the ranges, in the library's words for both faces
    if (!std::isfinite(g.spacing) || g.spacing < 0) {
        throw invalid_field("--spacing", std::to_string(g.spacing), "must be finite and >= 0");
    }
    return geometry;
}

}  // namespace pinmask::cli
