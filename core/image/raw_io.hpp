// Camera RAW files through LibRaw (DNG, CR2, CR3, NEF, ARW, RAF, ORF, RW2, PEF, ... whatever the
// installed LibRaw reads) as unprocessed sensor data: no demosaicing interpolation, no white
// balance, no colour matrix, no gamma.
// Values are counts above the black level: raw - black(r, c), where black(r, c) is LibRaw's
// documented sum color.black + color.cblack[colour of (r, c)] + the block pattern
// color.cblack[6 + (r mod cblack[4]) * cblack[5] + (c mod cblack[5])] (when cblack[4], cblack[5]
// are set), all read from the file. Rows and columns are those of LibRaw's visible area
// (sizes.height x sizes.width, margins dropped). full_scale is color.maximum - color.black (the
// white level above black) times the number of samples summed.
// Bayer sensors (a 2 x 2 CFA with one R, two G, one B) give a half-resolution grey image, one
// pixel per 2 x 2 block (whose top-left is an even row and column; an odd last row/column is
// dropped), by `bayer`:
//   sum2x2  the sum of the block's four samples (default; the pixel pitch doubles);
//   green   the mean of its two green samples (alias: g);
//   r, b    its red or blue sample.
// Monochrome RAW (no CFA) is returned at full resolution, whatever `bayer` says. Other layouts
// (X-Trans, Foveon, linear DNG) are refused: they need interpolation.
// LibRaw runs in a child process (core/files/isolated_call), which sends back the visible area's
// raw counts and LibRaw's metadata; the interpretation above happens in the caller's process. A
// file that crashes LibRaw (Debian 12's 0.20.2 aborts on some malformed files) is refused with
// InvalidInput naming the file and how LibRaw died; the caller goes on. Costs one fork per file.
#pragma once

#include <filesystem>
#include <string>

#include "core/errors/field_names.hpp"
#include "core/image/image_io.hpp"

namespace pinmask {

enum class BayerMode { kSum2x2, kGreen, kRed, kBlue };

// "sum2x2", "green", "g", "r", "b"; InvalidInput naming `field` otherwise.
BayerMode parse_bayer_mode(const std::string& name, const std::string& field = field_ref("bayer"));
std::string bayer_mode_name(BayerMode mode);

struct RawInfo {
    std::string camera;  // make and model from the file
    int binning = 1;     // output pixel = binning x binning sensor pixels (2 for Bayer)
    std::string bayer;   // the mode used ("" for monochrome)
    double black = 0.0;  // color.black (the common part)
    double white = 0.0;  // color.maximum
    // One sentence for stderr / stats, e.g. the doubled pixel pitch; settings as field_ref.
    std::string note;
};

// True for the extensions read as camera RAW (case-insensitive): .dng .cr2 .cr3 .crw .nef .nrw
// .arw .srf .sr2 .raf .orf .rw2 .rwl .pef .srw .3fr .erf .kdc .dcr .mrw .mos .iiq .x3f .raw.
bool is_raw_extension(const std::filesystem::path& path);

// Reads a RAW file as described above. Throws InvalidInput ("camera RAW file '<path>': <LibRaw's
// reason>") for files LibRaw cannot open or unpack or that crash it, unsupported layouts, and
// ResourceLimit for a declared size beyond kMaxImageSamples or the memory bound (checked before
// unpacking); RuntimeFailure if no child process can be started.
LoadedImage read_raw(const std::filesystem::path& path, BayerMode mode = BayerMode::kSum2x2,
                     RawInfo* info = nullptr);

// read_image for every format, with RAW (by extension) read in `mode`: the entry point for
// captures and dark frames.
LoadedImage read_capture(const std::filesystem::path& path, BayerMode mode,
                         RawInfo* info = nullptr);

}  // namespace pinmask
