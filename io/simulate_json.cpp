#include "io/simulate_json.hpp"

#include "core/fft/fft.hpp"
#include "design/psf/kernel_model.hpp"
#include "io/mask_json.hpp"
#include "io/noise_json.hpp"

namespace pinmask::io {

using nlohmann::ordered_json;

ordered_json background_json(const SimulatedCapture& s) {
    ordered_json background = ordered_json::array();
    for (double b : s.background) background.push_back(b);
    return background;
}

ordered_json simulate_config_json(const SimulateConfigInputs& in, const Mask& mask,
                                  const SimulatePipelineOptions& po,
                                  const SimulatePipelineResult& r,
                                  const std::vector<std::string>& explain) {
    const SimulatedCapture& s = r.capture;
    const SimulatePipelineSummary& sum = r.summary;
    const int m = sum.period_px;

    return {
        {"format", "pinmask-simulate-config"},
        {"version", 1},
        {"mask",
         {{"path", in.mask_path},
          {"geometry_hash", geometry_hash(mask)},
          {"n", mask.pattern.n},
          {"holes", sum.holes},
          {"pixels_per_cell", mask.psf.pixels_per_cell}}},
        {"psf",
         {{"period_px", m},
          {"kernel", kernel_model_name(sum.kernel.model)},
          {"kernel_reason", sum.kernel.model_reason},
          {"kernel_enclosed_energy", sum.kernel.enclosed_energy},
          {"kernel_support_capped", sum.kernel.support_capped},
          {"centring", "central element (floor(m/2), floor(m/2)) is the zero shift (deconvwnr)"}}},
        {"scene",
         {{"name", sum.scene_name}, {"rows", m}, {"cols", m}, {"channels", sum.scene_channels}}},
        {"forward_model", "cyclic: circular convolution over one period"},
        {"geometry", in.geometry},
        {"full_sensor",
         {{"enabled", in.full_sensor},
          {"rows", s.capture.rows()},
          {"cols", s.capture.cols()},
          {"period_origin_row", s.origin.row},
          {"period_origin_col", s.origin.col},
          {"whole_period_on_sensor", s.whole_period_on_sensor}}},
        {"noise", io::noise_json(po.sim.noise)},
        {"seed", in.seed},
        {"precision", sum.single_precision ? "single" : "double"},
        {"threads", fft_threads()},
        {"units", po.sim.noise.kind == NoiseKind::kPhoton
                      ? "electrons / (photons_per_pinhole * holes); a uniform noiseless scene "
                        "of value v gives v plus the background"
                      : "normalised: a uniform noiseless scene of value v gives v"},
        {"background_per_channel", background_json(s)},
        {"outputs",
         {{"capture", in.output},
          {"dark_frame",
           in.dark_frame.empty() ? ordered_json(nullptr) : ordered_json(in.dark_frame)},
          {"config", in.output + ".config.json"}}},
        {"explain", explain}};
}

ordered_json simulate_summary_json(const SimulateConfigInputs& in, const SimulatePipelineResult& r,
                                   const NoiseModel& noise) {
    const SimulatedCapture& s = r.capture;
    return ordered_json{
        {"capture", in.output},
        {"config", in.output + ".config.json"},
        {"dark_frame", in.dark_frame.empty() ? ordered_json(nullptr) : ordered_json(in.dark_frame)},
        {"rows", s.capture.rows()},
        {"cols", s.capture.cols()},
        {"channels", s.capture.n_channels()},
        {"period_px", r.summary.period_px},
        {"noise", io::noise_json(noise)},
        {"background_per_channel", background_json(s)}};
}

}  // namespace pinmask::io
