#include "core/raw_io.hpp"

#include <libraw/libraw.h>

#include <algorithm>
#include <array>
#include <memory>
#include <set>

#include "core/error.hpp"
#include "core/image_io_detail.hpp"

namespace pinmask {
namespace fs = std::filesystem;

BayerMode parse_bayer_mode(const std::string& name, const std::string& field) {
    if (name == "sum2x2") return BayerMode::kSum2x2;
    if (name == "green" || name == "g") return BayerMode::kGreen;
    if (name == "r") return BayerMode::kRed;
    if (name == "b") return BayerMode::kBlue;
    throw invalid_field(field, name, "must be one of sum2x2, green (alias g), r, b");
}

std::string bayer_mode_name(BayerMode mode) {
    switch (mode) {
        case BayerMode::kSum2x2:
            return "sum2x2";
        case BayerMode::kGreen:
            return "green";
        case BayerMode::kRed:
            return "r";
        default:
            return "b";
    }
}

bool is_raw_extension(const fs::path& path) {
    static const std::set<std::string> kExt = {".dng", ".cr2", ".cr3", ".crw", ".nef", ".nrw",
                                               ".arw", ".srf", ".sr2", ".raf", ".orf", ".rw2",
                                               ".rwl", ".pef", ".srw", ".3fr", ".erf", ".kdc",
                                               ".dcr", ".mrw", ".mos", ".iiq", ".x3f", ".raw"};
    std::string e = path.extension().string();
    std::transform(e.begin(), e.end(), e.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return kExt.count(e) > 0;
}

namespace {

InvalidInput bad_raw(const fs::path& path, const std::string& problem) {
    return InvalidInput("camera RAW file '" + path.string() + "': " + problem);
}

// LibRaw reports corrupt data through a callback (its default prints to stderr, which a library
// must not do): record the first report and refuse the file after unpacking.
void record_data_error(void* data, const char* /*file*/, const int offset) {
    auto* first = static_cast<int*>(data);
    if (*first == -2) *first = offset;
}

}  // namespace

LoadedImage read_raw(const fs::path& path, BayerMode mode, RawInfo* info_out) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) throw bad_raw(path, "file does not exist");
    if (fs::file_size(path, ec) == 0) throw bad_raw(path, "file is empty");
    auto raw = std::make_unique<LibRaw>();
    int data_error = -2;  // -2: none; -1: unexpected end of file; else the offset
    raw->set_dataerror_handler(record_data_error, &data_error);
    int ret = raw->open_file(path.c_str());
    if (ret != LIBRAW_SUCCESS) throw bad_raw(path, std::string("LibRaw: ") + libraw_strerror(ret));
    const auto& S = raw->imgdata.sizes;
    const long long rows = S.height, cols = S.width;
    // Before unpacking: the raw buffer (2 bytes a sample) plus our doubles.
    detail::check_image_size(path, rows, cols, 1, 2.0 * double(S.raw_height) * S.raw_width);
    ret = raw->unpack();
    if (ret != LIBRAW_SUCCESS) throw bad_raw(path, std::string("LibRaw: ") + libraw_strerror(ret));
    if (data_error != -2)
        throw bad_raw(path,
                      "LibRaw: corrupt data: " +
                          (data_error == -1 ? std::string("unexpected end of file")
                                            : "bad data at offset " + std::to_string(data_error)));
    const auto& R = raw->imgdata.rawdata;
    const auto& C = raw->imgdata.color;
    const unsigned filters = raw->imgdata.idata.filters;
    if (!R.raw_image) {
        throw bad_raw(path,
                      "not a Bayer or monochrome sensor image (LibRaw gives no single-"
                      "plane raw data: X-Trans/Foveon/linear DNG need interpolation)");
    }
    if (filters == 9) throw bad_raw(path, "X-Trans sensor: its 6 x 6 CFA has no 2 x 2 binning");
    if (rows < 1 || cols < 1 || S.top_margin + rows > S.raw_height ||
        S.left_margin + cols > S.raw_width || S.raw_pitch < 2 * S.raw_width)
        throw bad_raw(path, "inconsistent sizes (visible area outside the raw frame)");
    const std::size_t pitch = S.raw_pitch / 2;
    auto black_at = [&](int r, int c, int colour) {
        double b = C.black + (colour >= 0 && colour < 4 ? C.cblack[colour] : 0);
        if (C.cblack[4] && C.cblack[5]) {
            const std::size_t k = 6 + (r % C.cblack[4]) * C.cblack[5] + (c % C.cblack[5]);
            if (k < LIBRAW_CBLACK_SIZE) b += C.cblack[k];
        }
        return b;
    };
    auto value = [&](int r, int c) {
        const int colour = filters ? raw->COLOR(r, c) : 0;
        const double v =
            R.raw_image[(r + S.top_margin) * pitch + static_cast<std::size_t>(c + S.left_margin)];
        return v - black_at(r, c, colour);
    };
    RawInfo info;
    info.camera = std::string(raw->imgdata.idata.make) + " " + raw->imgdata.idata.model;
    info.black = C.black;
    info.white = C.maximum;
    const double span = double(C.maximum) - double(C.black);
    if (!(span > 0)) throw bad_raw(path, "white level not above the black level");
    LoadedImage out;
    out.format = SampleFormat::kUint16;
    if (!filters) {
        Plane p(rows, cols);
        for (int r = 0; r < rows; ++r)
            for (int c = 0; c < cols; ++c) p(r, c) = value(r, c);
        out.image = Image(std::move(p));
        out.full_scale = span;
        info.note = "monochrome RAW: full resolution, --bayer does not apply";
    } else {
        // The 2 x 2 CFA of the first block must hold R, B and two G (colours 1 and 3 are green).
        std::array<int, 4> count{};
        for (int r = 0; r < 2; ++r)
            for (int c = 0; c < 2; ++c) ++count[static_cast<std::size_t>(raw->COLOR(r, c) & 3)];
        if (count[0] != 1 || count[2] != 1 || count[1] + count[3] != 2)
            throw bad_raw(path, "the CFA is not a 2 x 2 Bayer pattern (RGGB, BGGR, GRBG, GBRG)");
        if (rows < 2 || cols < 2) throw bad_raw(path, "smaller than one 2 x 2 Bayer block");
        const int hr = static_cast<int>(rows / 2), hc = static_cast<int>(cols / 2);
        Plane p = Plane::Zero(hr, hc);
        for (int r = 0; r < hr; ++r)
            for (int c = 0; c < hc; ++c) {
                double sum = 0, green = 0, red = 0, blue = 0;
                for (int a = 0; a < 2; ++a)
                    for (int b = 0; b < 2; ++b) {
                        const int rr = 2 * r + a, cc = 2 * c + b;
                        const double v = value(rr, cc);
                        const int colour = raw->COLOR(rr, cc);
                        sum += v;
                        if (colour == 1 || colour == 3) green += 0.5 * v;
                        if (colour == 0) red = v;
                        if (colour == 2) blue = v;
                    }
                p(r, c) = mode == BayerMode::kSum2x2  ? sum
                          : mode == BayerMode::kGreen ? green
                          : mode == BayerMode::kRed   ? red
                                                      : blue;
            }
        out.image = Image(std::move(p));
        out.full_scale = mode == BayerMode::kSum2x2 ? 4 * span : span;
        info.binning = 2;
        info.bayer = bayer_mode_name(mode);
        info.note = "Bayer RAW read as " + info.bayer + ": " + std::to_string(hc) + " x " +
                    std::to_string(hr) +
                    " px, one pixel per 2 x 2 block: the pixel pitch is "
                    "twice the sensor's";
    }
    if (info_out) *info_out = info;
    return out;
}

LoadedImage read_capture(const fs::path& path, BayerMode mode, RawInfo* info) {
    if (is_raw_extension(path)) return read_raw(path, mode, info);
    if (info) *info = RawInfo{};
    return read_image(path);
}

}  // namespace pinmask
