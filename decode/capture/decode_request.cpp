#include "decode/capture/decode_request.hpp"

#include <optional>
#include <string>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/errors/name_table.hpp"
#include "decode/solvers/decode_method.hpp"
#include "decode/solvers/decode_modes.hpp"

namespace pinmask {

const char* method_parameter_field(MethodParameter p) {
    static constexpr NameTable<MethodParameter, 8> kFields{
        {{MethodParameter::kNsr, "nsr"},
         {MethodParameter::kLambda, "lambda"},
         {MethodParameter::kRegulariser, "regulariser"},
         {MethodParameter::kEps, "eps"},
         {MethodParameter::kNoiseSigma, "noise_sigma"},
         {MethodParameter::kNonnegative, "nonnegative"},
         {MethodParameter::kIterations, "iterations"},
         {MethodParameter::kTolerance, "tolerance"}}};
    return name_or(kFields, p, "?");
}

bool write_method_parameter(DecodeOptions& d, MethodParameter p, const DecodeRequest& r) {
    const DecodeMethod m = d.method;
    switch (p) {
        case MethodParameter::kNsr:
            if (m != DecodeMethod::kWiener) return false;
            d.wiener.nsr = r.nsr;
            d.wiener.automatic = r.nsr_auto;
            return true;
        case MethodParameter::kLambda:
            if (m == DecodeMethod::kTikhonov) d.tikhonov.lambda = r.lambda;
            if (m == DecodeMethod::kTikhonov) d.tikhonov.automatic = r.lambda_auto;
            if (m == DecodeMethod::kTv) d.tv.lambda = r.lambda;
            if (m == DecodeMethod::kTv) d.tv.automatic = r.lambda_auto;
            return m == DecodeMethod::kTikhonov || m == DecodeMethod::kTv;
        case MethodParameter::kRegulariser:
            if (m != DecodeMethod::kTikhonov) return false;
            d.tikhonov.regulariser = r.regulariser;
            return true;
        case MethodParameter::kEps:
            if (m != DecodeMethod::kTvqc) return false;
            d.tvqc.eps = r.eps;
            return true;
        case MethodParameter::kNoiseSigma:
            if (m != DecodeMethod::kTvqc) return false;
            d.tvqc.noise_sigma = r.noise_sigma;
            return true;
        case MethodParameter::kNonnegative:
            if (m == DecodeMethod::kTv) d.tv.nonnegative = r.nonnegative;
            if (m == DecodeMethod::kTvqc) d.tvqc.nonnegative = r.nonnegative;
            return m == DecodeMethod::kTv || m == DecodeMethod::kTvqc;
        case MethodParameter::kIterations:
            if (!is_iterative(m)) return false;
            d.iterative.max_iterations = r.iterations;
            return true;
        case MethodParameter::kTolerance:
            if (!is_iterative(m)) return false;
            d.iterative.tolerance = r.tolerance;
            return true;
    }
    return false;
}

void resolve_implied_method(DecodeRequest& r, const std::vector<GivenParameter>& given,
                            bool nsr_map_given) {
    if (!r.method_auto) return;
    std::optional<DecodeMethod> implied;
    std::string by, by_value;
    const auto imply = [&](DecodeMethod m, const std::string& field, const std::string& value) {
        if (implied && *implied != m) {
            throw invalid_field(field_ref(field), value,
                                "is read by " + std::string(decode_method_name(m)) + " but " +
                                    field_ref(by) + (by_value.empty() ? "" : " " + by_value) +
                                    " is read by " + decode_method_name(*implied) + " only; give " +
                                    field_ref("method") + " to say which");
        }
        if (!implied) implied = m, by = field, by_value = value;
    };
    if (nsr_map_given) imply(DecodeMethod::kWiener, "nsr_map", "");
    for (const GivenParameter& g : given) {
        const char* field = method_parameter_field(g.parameter);
        std::optional<DecodeMethod> reader;
        std::string users;
        for (DecodeMethod m : kDecodeMethods) {
            DecodeOptions probe;
            probe.method = m;
            if (!write_method_parameter(probe, g.parameter, r)) continue;
            users += (users.empty() ? "" : ", ") + std::string(decode_method_name(m));
            for (DecodeMethod a : kAutoMethods)
                if (a == m) reader = m;
        }
        if (!reader) {
            throw invalid_field(field_ref(field), g.value,
                                "is not used by " + field_ref("method") +
                                    " auto (wiener or tv, chosen from the capture; only by " +
                                    users + "); give " + field_ref("method") + " " + users);
        }
        imply(*reader, field, g.value);
    }
    if (!implied) return;
    r.method = *implied;
    r.method_auto = false;
    r.method_implied_by = by;
}

void refuse_unused_parameters(const DecodeRequest& r, const std::vector<GivenParameter>& given) {
    const DecodeMethod m = r.method;
    for (const GivenParameter& g : given) {
        DecodeOptions probe;
        probe.method = m;
        if (write_method_parameter(probe, g.parameter, r)) continue;
        std::string users;
        for (DecodeMethod other : kDecodeMethods) {
            probe.method = other;
            if (write_method_parameter(probe, g.parameter, r))
                users += (users.empty() ? "" : ", ") + std::string(decode_method_name(other));
        }
        throw invalid_field(field_ref(method_parameter_field(g.parameter)), g.value,
                            "is not used by " + field_ref("method") + " " + decode_method_name(m) +
                                " (only by " + users + "); remove it or choose that method");
    }
    if (m == DecodeMethod::kTikhonov && !r.lambda_auto && !(r.lambda > 0.0)) {
        throw invalid_field(field_ref("lambda"), std::to_string(r.lambda),
                            "must be > 0 for tikhonov: lambda 0 is the unregularised inverse "
                            "filter, which multiplies noise by 1/|H| at the PSF's spectral "
                            "near-zeros (use " +
                                field_ref("method") + " wiener " + field_ref("nsr") +
                                " 0 for the floored inverse)");
    }
}

DecodeOptions decode_options(const DecodeRequest& r) {
    DecodeOptions d;
    d.model = r.model;
    // Each method writes its own struct (and the iterative ones the shared iterative options):
    // method auto fills both candidates' so the pipeline can run either.
    if (r.method_auto) {
        for (DecodeMethod m : kAutoMethods) {
            d.method = m;
            for (MethodParameter p : kMethodParameters) write_method_parameter(d, p, r);
        }
    }
    d.method = r.method;
    for (MethodParameter p : kMethodParameters) write_method_parameter(d, p, r);
    return d;
}

CaptureDecodeOptions capture_decode_options(const DecodeRequest& r) {
    CaptureDecodeOptions o;
    o.crop = r.crop;
    o.crop_auto = r.crop_auto;
    o.model_auto = r.model_auto;
    o.nonnegative_auto = r.nonnegative_auto;
    o.method_auto = r.method_auto;
    o.method_implied_by = r.method_implied_by;
    o.background = r.background.mode;
    o.background_value = r.background.value;
    o.downsample = r.downsample;
    o.normalize = r.normalize;
    o.decode = decode_options(r);
    o.precision = r.precision;
    o.threads = r.threads;
    return o;
}

}  // namespace pinmask
