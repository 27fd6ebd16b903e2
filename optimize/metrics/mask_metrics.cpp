#include "optimize/metrics/mask_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/fft/fft.hpp"
#include "core/limits/resource_limits.hpp"
#include "core/units/number_format.hpp"
#include "design/psf/kernel_model.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/robust_wiener.hpp"

namespace pinmask {
namespace {

ScenePrior sampled_prior(const PriorSpec& spec, int m) {
    std::vector<Plane> planes;
    for (int i = 0; i < spec.count; ++i) {
        const std::uint64_t seed = spec.first_seed + static_cast<std::uint64_t>(i);
        planes.push_back(spec.kind == PriorKind::kText ? text_scene(m, m, seed)
                                                       : stars_scene(m, m, seed));
    }
    return scene_prior_from_images(planes, spec.description());
}

}  // namespace

const std::vector<std::pair<PriorKind, std::string>>& prior_kind_names() {
    static const std::vector<std::pair<PriorKind, std::string>> kNames{
        {PriorKind::kNatural, "natural"},
        {PriorKind::kText, "text"},
        {PriorKind::kStars, "stars"},
        {PriorKind::kFiles, "files"}};
    return kNames;
}

std::string prior_kind_name(PriorKind kind) {
    for (const auto& [k, name] : prior_kind_names())
        if (k == kind) return name;
    return "unknown";
}

void PriorSpec::validate() const {
    if (kind == PriorKind::kFiles) {
        if (files.empty())
            throw invalid_field(field_ref("prior"), "''", "needs at least one image file");
        return;
    }
    if (count < 1 || count > kMaxPriorScenes) {
        throw invalid_field(field_ref("prior.count"), std::to_string(count),
                            "must be between 1 and 4096 (sample scenes averaged for the prior; "
                            "the average settles long before 4096)");
    }
}

std::string PriorSpec::description() const {
    std::ostringstream s;
    switch (kind) {
        case PriorKind::kNatural:
            s << "natural (" << count << " 1/f textures, seeds " << first_seed << ".."
              << first_seed + count - 1 << ")";
            break;
        case PriorKind::kText:
            s << "text (" << count << " pages of random words, seeds " << first_seed << ".."
              << first_seed + count - 1 << ")";
            break;
        case PriorKind::kStars:
            s << "stars (" << count << " sparse star fields, seeds " << first_seed << ".."
              << first_seed + count - 1 << ")";
            break;
        case PriorKind::kFiles: {
            s << "files (";
            for (std::size_t i = 0; i < files.size(); ++i)
                s << (i ? ", " : "") << files[i].string();
            s << ")";
            break;
        }
    }
    return s.str();
}

PriorSpec parse_prior_spec(const std::string& text, int count) {
    PriorSpec p;
    p.count = count;
    if (text == "natural") {
        p.kind = PriorKind::kNatural;
    } else if (text == "text") {
        p.kind = PriorKind::kText;
    } else if (text == "stars") {
        p.kind = PriorKind::kStars;
    } else {
        p.kind = PriorKind::kFiles;
        std::istringstream in(text);
        std::string item;
        while (std::getline(in, item, ',')) {
            if (item.empty())
                throw invalid_field(field_ref("prior"), "'" + text + "'", "has an empty item");
            if (!std::filesystem::is_regular_file(item)) {
                throw invalid_field(field_ref("prior"), item,
                                    "is neither natural, text, stars nor an existing image file");
            }
            p.files.push_back(item);
        }
    }
    p.validate();
    return p;
}

ScenePrior make_scene_prior(const PriorSpec& spec, int m) {
    spec.validate();
    switch (spec.kind) {
        case PriorKind::kNatural: {
            ScenePrior p = natural_scene_prior(m, m, spec.count, spec.first_seed, 1.0);
            p.source = spec.description();
            return p;
        }
        case PriorKind::kText:
        case PriorKind::kStars:
            return sampled_prior(spec, m);
        case PriorKind::kFiles:
            break;
    }
    std::vector<Plane> planes;
    for (const auto& f : spec.files) {
        SceneSpec s;
        s.kind = SceneKind::kFile;
        s.path = f;
        for (Plane& ch : make_scene(s, m, m).channels) planes.push_back(std::move(ch));
    }
    return scene_prior_from_images(planes, spec.description());
}

PriorRelevance prior_relevance(const ScenePrior& prior, double fraction) {
    const Plane& S = prior.power;
    const int rows = prior.rows(), cols = prior.cols();
    double peak = 0.0;
    for (int k = 0; k < rows; ++k)
        for (int l = 0; l < cols; ++l)
            if (k != 0 || l != 0) peak = std::max(peak, S(k, l));
    PriorRelevance r;
    for (int k = 0; k < rows; ++k)
        for (int l = 0; l < cols; ++l) {
            if (k == 0 && l == 0) continue;
            ++r.total;
            if (S(k, l) < fraction * peak) {
                ++r.irrelevant;
            } else {
                const double fk = std::min(k, rows - k), fl = std::min(l, cols - l);
                r.highest_relevant_radius = std::max(r.highest_relevant_radius, std::hypot(fk, fl));
            }
        }
    return r;
}

NoiseLevel noise_level(const NoiseModel& model) {
    NoiseLevel l{model, ""};
    switch (model.kind) {
        case NoiseKind::kNone:
            l.key = "noiseless";
            break;
        case NoiseKind::kGaussianSnr:
            l.key = "snr" + format_number(model.snr_db);
            break;
        case NoiseKind::kPhoton:
            l.key = "ph" + format_number(model.photons_per_pinhole);
            break;
    }
    return l;
}

void MaskMetricsOptions::validate() const {
    if (noise.empty()) {
        throw InvalidInput(field_ref("snr_db") + "/" + field_ref("photons") +
                           ": at least one noise level is needed");
    }
    for (const NoiseLevel& l : noise) pinmask::validate(l.model);
    prior.validate();
    if ((wiener || tv) && scenes.empty()) {
        throw invalid_field(field_ref("scenes"), "''",
                            "needs at least one scene for simulated metrics");
    }
    simulation.validate();
    robust.validate();
    if (depth) {
        depth_range.validate();
        for (const NoiseLevel& l : noise) depth_fisher_noise(l.model, 1);
    }
    if (!(spectral_zero_threshold > 0.0 && spectral_zero_threshold < 1.0)) {
        throw invalid_field("spectral_zero_threshold", format_number(spectral_zero_threshold),
                            "must be in (0, 1) (a fraction of the flat level sqrt(K))");
    }
}

MetricsContext::MetricsContext(MaskMetricsOptions options) : options_(std::move(options)) {
    options_.validate();
}

const std::vector<NamedScene>& MetricsContext::scenes(int m) {
    auto it = scenes_.find(m);
    if (it != scenes_.end()) return it->second;
    check_memory(8.0 * m * m * (3.0 * options_.scenes.size() + 1.0), "scenes at the period");
    std::vector<NamedScene> out;
    for (const SceneSpec& s : options_.scenes) out.push_back({scene_name(s), make_scene(s, m, m)});
    return scenes_.emplace(m, std::move(out)).first->second;
}

const ScenePrior& MetricsContext::prior(int m) {
    auto it = priors_.find(m);
    if (it != priors_.end()) return *it->second;
    check_memory(8.0 * m * m * 4.0, "scene prior at the period");
    auto p = std::make_shared<ScenePrior>(make_scene_prior(options_.prior, m));
    return *priors_.emplace(m, std::move(p)).first->second;
}

MaskMetrics compute_mask_metrics(const Mask& mask, MetricsContext& context) {
    const MaskMetricsOptions& o = context.options();
    MaskMetrics r;
    r.n = mask.pattern.n;
    r.holes = static_cast<int>(mask.pattern.pinholes.size());
    r.pixels_per_cell = mask.psf.pixels_per_cell;
    r.period_px = r.n * r.pixels_per_cell;
    const int n = r.n, ppc = r.pixels_per_cell, m = r.period_px;
    const ComplexPlane spectrum = pattern_spectrum(mask.pattern);
    if (o.sidelobes) r.sidelobes = sidelobe_metrics_from_spectrum(spectrum);
    const bool simulated = o.wiener || o.tv;
    if (!(o.spectrum || o.analytic || simulated || o.depth)) return r;
    std::vector<DepthSlope> depth_slopes;
    if (o.depth) {
        for (double u : depth_samples(mask, o.depth_range))
            depth_slopes.push_back(depth_slope(mask, u, 0, 0));
    }
    Kernel kernel;
    ComplexPlane kernel_otf;
    if (o.spectrum || o.analytic || simulated) {
        check_psf_memory(n, ppc, 4, 3);  // PSF, kernel, two scene planes; kernel and OTF spectra
        kernel = mask_kernel(mask);
        std::ostringstream s;
        s << kernel_model_name(kernel.model) << " (" << kernel.model_reason << "), "
          << kernel.values.rows() << " x " << kernel.values.cols() << " px, enclosed energy "
          << kernel.enclosed_energy;
        r.kernel_description = s.str();
        kernel_otf = expand_half_spectrum(kernel_spectrum(kernel, n, ppc), m);
    }
    if (o.spectrum) {
        r.spectrum = pattern_spectrum_metrics(spectrum);
        r.otf = otf_condition(spectrum, kernel_otf);
        r.spectral_zero = find_spectral_zero(spectrum, pattern_frequencies_passed(kernel_otf, n),
                                             o.spectral_zero_threshold);
    }
    Plane psf;
    if (simulated) psf = synthesize_psf(mask.pattern, kernel, ppc);
    for (const NoiseLevel& level : o.noise) {
        LevelMetrics lm;
        lm.level = level;
        if (o.analytic) {
            const AnalyticWienerModel model(kernel_otf, context.prior(m), level.model);
            const WeightChoice& nsr = o.simulation.wiener_nsr;
            const AnalyticError e =
                nsr.tuned ? model.evaluate_tuned_nsr(spectrum)
                          : model.evaluate(spectrum, {WienerFilterKind::kFixedNsr, nsr.value});
            const AnalyticError best = model.evaluate(spectrum, {WienerFilterKind::kOptimal, 0.0});
            lm.analytic = AnalyticFigures{e.psnr_db, e.nsr, best.psnr_db};
            if (o.robust.any()) {
                const RobustWienerModel rm(mask, o.robust, context.prior(m), level.model);
                const RobustError re = rm.evaluate(spectrum, {WienerFilterKind::kFixedNsr, e.nsr});
                lm.robust = RobustFigures{re.psnr_db, e.psnr_db - re.psnr_db};
            }
        }
        if (o.wiener) {
            lm.wiener = simulated_quality(psf, context.scenes(m), level.model, r.holes, n * n,
                                          SimulatedDecoder::kWiener, o.simulation);
        }
        if (o.tv) {
            lm.tv = simulated_quality(psf, context.scenes(m), level.model, r.holes, n * n,
                                      SimulatedDecoder::kTv, o.simulation);
        }
        if (o.depth)
            lm.depth = depth_figures(depth_slopes, depth_fisher_noise(level.model, r.holes));
        r.levels.push_back(std::move(lm));
    }
    return r;
}

}  // namespace pinmask
