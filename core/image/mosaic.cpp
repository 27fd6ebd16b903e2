#include "core/image/mosaic.hpp"

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"

namespace pinmask {
namespace {

std::string size_text(Eigen::Index rows, Eigen::Index cols) {
    return std::to_string(cols) + " x " + std::to_string(rows) + " (W x H)";
}

}  // namespace

Plane sum_2x2_blocks(const Plane& p, const std::string& what) {
    const Eigen::Index rows = p.rows() / 2, cols = p.cols() / 2;
    if (rows < 1 || cols < 1)
        throw InvalidInput(what + ": " + size_text(p.rows(), p.cols()) +
                           " is smaller than one 2 x 2 Bayer block");
    Plane out(rows, cols);
    for (Eigen::Index r = 0; r < rows; ++r)
        for (Eigen::Index c = 0; c < cols; ++c)
            out(r, c) = p(2 * r, 2 * c) + p(2 * r, 2 * c + 1) + p(2 * r + 1, 2 * c) +
                        p(2 * r + 1, 2 * c + 1);
    return out;
}

LoadedImage read_capture_as_mosaic(const std::filesystem::path& path, BayerMode bayer,
                                   RawInfo* info) {
    if (is_raw_extension(path)) return read_raw(path, bayer, info);
    LoadedImage in = read_image(path);
    const std::string name = bayer_mode_name(bayer);
    if (in.image.n_channels() != 1) {
        throw invalid_field(field_ref("bayer"), name,
                            "applies to a single-channel Bayer mosaic; " + path.string() + " has " +
                                std::to_string(in.image.n_channels()) +
                                " channels (already colour, not a mosaic): leave it out");
    }
    if (bayer != BayerMode::kSum2x2) {
        throw invalid_field(field_ref("bayer"), name,
                            "needs the colour-filter pattern, which a camera RAW file holds and " +
                                path.string() +
                                " (an image file) does not: only sum2x2 applies to a mosaic "
                                "saved as an image");
    }
    LoadedImage out;
    out.format = SampleFormat::kFloat64;
    out.full_scale = 4 * in.full_scale;
    out.image = Image(sum_2x2_blocks(in.image.channels[0], path.string()));
    RawInfo r;
    r.binning = 2;
    r.bayer = name;
    r.note = "Bayer mosaic in an image file read as sum2x2: " + std::to_string(out.image.cols()) +
             " x " + std::to_string(out.image.rows()) +
             " px, one pixel per 2 x 2 block: the pixel pitch is twice the sensor's";
    if (info) *info = r;
    return out;
}

namespace {

// "the capture, read at half resolution (bayer B), is W x H; the PSF is W x H"
std::string sampling_sizes(int psf_rows, int psf_cols, int capture_rows, int capture_cols,
                           const RawInfo& info) {
    return "the capture, read at half resolution (" + field_ref("bayer") + " " + info.bayer +
           "), is " + size_text(capture_rows, capture_cols) + "; the PSF is " +
           size_text(psf_rows, psf_cols);
}

// The relation of a PSF's size to a capture's sampling: false when the PSF is taken as it is,
// true when it is the sensor's full resolution for a sum2x2 capture (to be summed 2 x 2); every
// other PSF larger than a binned capture is refused here (InvalidInput naming field_ref("bayer")).
bool psf_needs_binning(int psf_rows, int psf_cols, int capture_rows, int capture_cols,
                       const RawInfo& info) {
    if (info.binning != 2) return false;
    if (psf_rows <= capture_rows && psf_cols <= capture_cols) return false;
    const bool twice = (psf_rows == 2 * capture_rows || psf_rows == 2 * capture_rows + 1) &&
                       (psf_cols == 2 * capture_cols || psf_cols == 2 * capture_cols + 1);
    if (twice && info.bayer == "sum2x2") return true;
    const std::string sizes = sampling_sizes(psf_rows, psf_cols, capture_rows, capture_cols, info);
    if (twice) {
        throw invalid_field(field_ref("bayer"), info.bayer,
                            sizes +
                                ", the sensor's full resolution, whose colour sites are "
                                "unknown: it cannot be sampled as the capture was; give "
                                "sum2x2 or a PSF at the capture's sampling");
    }
    throw invalid_field(field_ref("bayer"), info.bayer,
                        sizes +
                            ": larger than the capture and not twice its size, so not at "
                            "its sampling; give a PSF at the capture's sampling");
}

}  // namespace

void match_psf_to_binned_capture(Plane& psf, int capture_rows, int capture_cols,
                                 const RawInfo& info, std::string& note) {
    const int pr = static_cast<int>(psf.rows()), pc = static_cast<int>(psf.cols());
    if (!psf_needs_binning(pr, pc, capture_rows, capture_cols, info)) return;
    psf = sum_2x2_blocks(psf, "PSF");
    note = sampling_sizes(pr, pc, capture_rows, capture_cols, info) +
           ", the sensor's full resolution: its 2 x 2 blocks summed as the capture's";
}

void check_shared_psf_sampling(int psf_rows, int psf_cols, int capture_rows, int capture_cols,
                               const RawInfo& capture_info) {
    if (!psf_needs_binning(psf_rows, psf_cols, capture_rows, capture_cols, capture_info)) return;
    throw invalid_field(
        field_ref("psf"), size_text(psf_rows, psf_cols),
        "is the sensor's full resolution, and the capture " +
            size_text(capture_rows, capture_cols) + " is read at half resolution (" +
            field_ref("bayer") + " " + capture_info.bayer +
            "): one PSF serves every capture of a batch, so it is not binned per capture as a "
            "capture decoded alone is; give the PSF binned 2 x 2");
}

}  // namespace pinmask
