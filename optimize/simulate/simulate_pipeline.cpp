#include "optimize/simulate/simulate_pipeline.hpp"

#include <sstream>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/number_format.hpp"
#include "design/optics/working_distance.hpp"
#include "design/psf/kernel_model.hpp"
#include "design/psf/psf.hpp"
#include "design/psf/psf_exact.hpp"

namespace pinmask {
namespace {

std::string size_token(const Size2& s) {
    return std::to_string(s.cols) + "x" + std::to_string(s.rows);
}

// The --explain line of the noise model (none for the noiseless capture).
void explain_noise(const SimulatePipelineOptions& o, const SimulatedCapture& s,
                   std::vector<std::string>& explain) {
    const SimulationOptions& sim = o.sim;
    const NoiseModel& nm = sim.noise;
    const auto& given = o.photon_stages;
    const std::string seed = " (seed " + std::to_string(sim.seed) + ")";
    if (nm.kind == NoiseKind::kGaussianSnr) {
        explain.push_back("noise: Gaussian at " + format_number(nm.snr_db) +
                          " dB SNR, one draw per pixel" + seed);
    } else if (nm.kind == NoiseKind::kPhoton) {
        std::string stages = "Poisson signal";
        if (given.leak)
            stages += " + film leak (OD " + format_number(nm.film_optical_density) + ")";
        if (given.dark_current) stages += " + dark current";
        if (given.read_noise) stages += ", read noise";
        if (given.saturation) stages += ", saturation";
        if (given.adc) stages += ", " + std::to_string(nm.adc_bits) + "-bit ADC";
        explain.push_back("noise: photon model, " + format_number(nm.photons_per_pinhole) +
                          " e per pinhole, " + stages + seed);
        if (s.background[0] > 0.0) {
            explain.push_back(
                "background: the expected leak + dark current stays in the capture (" +
                format_number(s.background[0]) + " in channel 0), as a real sensor records it");
        }
    }
}

}  // namespace

void SimulatePipelineOptions::validate() const {
    if (sensor && !sim.full_sensor) {
        throw invalid_field(field_ref("sensor"), size_token(*sensor),
                            "only applies with " + field_ref("full_sensor"));
    }
    if (exact_geometry && (sim.full_sensor || sensor)) {
        throw invalid_field(sim.full_sensor ? field_ref("full_sensor") : field_ref("sensor"),
                            "given",
                            field_ref("exact_geometry") + " always covers the sensor (or " +
                                field_ref("window") + " ROWSxCOLS)");
    }
    if (!exact_geometry && (object_distance_m || window)) {
        throw invalid_field(window ? field_ref("window") : field_ref("object_distance_m"),
                            window ? size_token(*window) : format_length(*object_distance_m),
                            "only with " + field_ref("exact_geometry"));
    }
    sim.validate();
}

SimulatePipelineResult run_simulate_pipeline(const Mask& mask,
                                             const SimulatePipelineOptions& options) {
    options.validate();
    SimulatePipelineResult out;
    SimulatePipelineSummary& sum = out.summary;
    std::vector<std::string>& explain = sum.explain;
    SimulationOptions sim = options.sim;
    sum.kernel = mask_kernel(mask);
    const Kernel& kernel = sum.kernel;
    const Plane psf = synthesize_psf(mask.pattern, kernel, mask.psf.pixels_per_cell);
    const int m = static_cast<int>(psf.rows());
    sum.period_px = m;
    sum.holes = static_cast<int>(mask.pattern.pinholes.size());
    const int cells = mask.pattern.n * mask.pattern.n;
    explain.push_back("psf: synthesised from the mask, " + std::to_string(m) + " x " +
                      std::to_string(m) + " pixels per period, kernel " +
                      kernel_model_name(kernel.model) + " (" + kernel.model_reason + ")");
    const Image scene = make_scene(options.scene, m, m);
    sum.scene_name = scene_name(options.scene);
    sum.scene_channels = scene.n_channels();
    explain.push_back("scene: " + sum.scene_name + " rendered at one " + std::to_string(m) + " x " +
                      std::to_string(m) + " period, " + std::to_string(scene.n_channels()) +
                      " channel(s)");
    explain.push_back("capture: circular convolution scene (*) PSF over one period");

    if (sim.full_sensor) {
        sim.sensor_cols = options.sensor ? options.sensor->cols : mask.camera.sensor_cols;
        sim.sensor_rows = options.sensor ? options.sensor->rows : mask.camera.sensor_rows;
    } else {
        explain.push_back(
            "full-sensor tiling skipped: " + field_ref("full_sensor") +
            " not given, one period suffices (any one full period decodes the scene)");
    }
    Plane exact;  // exact geometry: what the sensor records (design/psf/psf_exact.hpp)
    if (options.exact_geometry) {
        ExactPsfOptions eo;
        eo.object_distance_m = options.object_distance_m.value_or(mask.camera.object_distance_m);
        check_object_distance(mask.camera, eo.object_distance_m,
                              field_ref("object_distance_m").c_str());
        if (options.window) {
            eo.rows = options.window->cols;  // typed ROWSxCOLS
            eo.cols = options.window->rows;
        }
        exact = exact_psf(mask, eo);
        sim.exact_psf = &exact;
        sum.object_distance_m = eo.object_distance_m;
        explain.push_back("geometry: exact at u = " + format_length(eo.object_distance_m) + ", " +
                          std::to_string(exact.rows()) + " x " + std::to_string(exact.cols()) +
                          " px, scene (*) exact PSF by linear convolution (the cyclic capture "
                          "above is replaced)");
    }
    // The convolution grid: one period, or the full linear convolution over the exact window.
    const long long grid_rows = options.exact_geometry ? exact.rows() + m - 1LL : m;
    const long long grid_cols = options.exact_geometry ? exact.cols() + m - 1LL : m;
    sum.single_precision = simulate_in_single(sim.precision, grid_rows, grid_cols);
    explain.push_back(std::string("precision: the convolution in ") +
                      (sum.single_precision ? "float32 (FFTW float)" : "double") + " on a " +
                      std::to_string(grid_rows) + " x " + std::to_string(grid_cols) + " grid (" +
                      field_ref("precision") + " " + precision_name(sim.precision) +
                      "; auto: float32 from 256 x 256)");
    out.capture = simulate_capture(scene, psf, sum.holes, cells, sim);
    const SimulatedCapture& s = out.capture;
    if (sim.full_sensor) {
        explain.push_back("full-sensor tiling: the period repeated over " +
                          std::to_string(sim.sensor_cols) + " x " +
                          std::to_string(sim.sensor_rows) +
                          " pixels (periodic extension, exact for the cyclic model), period "
                          "origin at column " +
                          std::to_string(s.origin.col) + ", row " + std::to_string(s.origin.row) +
                          " so the centred crop is the period");
    }
    explain_noise(options, s, explain);
    explain.insert(explain.end(), options.noise_notes.begin(), options.noise_notes.end());
    explain.push_back(sim.dark_frame
                          ? "dark frame: all-opaque film, same exposure, seed stream 1"
                          : "dark frame skipped: " + field_ref("dark_frame") + " not given");
    return out;
}

}  // namespace pinmask
