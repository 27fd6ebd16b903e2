#include "core/image/raw_io.hpp"

#include <libraw/libraw.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <set>
#include <vector>

#include "core/errors/error.hpp"
#include "core/errors/name_table.hpp"
#include "core/files/isolated_call.hpp"
#include "core/image/image_io_detail.hpp"

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
    static constexpr NameTable<BayerMode, 4> kNames{{{BayerMode::kSum2x2, "sum2x2"},
                                                     {BayerMode::kGreen, "green"},
                                                     {BayerMode::kRed, "r"},
                                                     {BayerMode::kBlue, "b"}}};
    return name_or(kNames, mode, "b");
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

// Every CFA LibRaw describes by `filters` (dcraw's 8 x 2 code, Leaf's 16 x 16 table, Fuji's
// rotated layout) repeats within kColourPeriod rows and columns; X-Trans (6 x 6) is refused.
constexpr int kColourPeriod = 16;
// The longest make-and-model string that crosses from the child (LibRaw's fields are 64 bytes).
constexpr std::size_t kMaxCameraName = 256;

// LibRaw's view of a file, uninterpreted: what the child process sends. Interpreting it (black
// levels, the Bayer check, binning) happens in the caller's process, where the fuzzer sees it.
struct RawFrame {
    int rows = 0, cols = 0;  // the visible area
    unsigned filters = 0;    // LibRaw's CFA code; 0: monochrome
    std::array<std::uint8_t, kColourPeriod * kColourPeriod> colour{};  // COLOR(r, c), r, c < 16
    double black = 0, maximum = 0;                                     // color.black, .maximum
    std::array<unsigned, LIBRAW_CBLACK_SIZE> cblack{};                 // color.cblack
    std::string camera;                                                // make and model
    std::vector<std::uint16_t> samples;  // rows x cols raw counts, row-major
    MemoryReservation samples_charge;    // the samples' bytes, against the memory budget
    int colour_at(int r, int c) const {
        return colour[static_cast<std::size_t>((r % kColourPeriod) * kColourPeriod +
                                               c % kColourPeriod)];
    }
};

// In the child: opens and unpacks the file with LibRaw and sends the frame (the visible area
// row by row, straight from LibRaw's buffer). LibRaw's crashes end the child, not the caller.
void send_frame(const fs::path& path, IsolatedWriter& w) {
    auto raw = std::make_unique<LibRaw>();
    int data_error = -2;  // -2: none; -1: unexpected end of file; else the offset
    raw->set_dataerror_handler(record_data_error, &data_error);
    int ret = raw->open_file(path.c_str());
    if (ret != LIBRAW_SUCCESS) throw bad_raw(path, std::string("LibRaw: ") + libraw_strerror(ret));
    const auto& S = raw->imgdata.sizes;
    const long long rows = S.height, cols = S.width;
    // Before unpacking: LibRaw's buffer (2 bytes a sample) beside the doubles the caller will
    // make (the caller checks its own budget again when the frame arrives).
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
    w.u64(static_cast<std::uint64_t>(rows));
    w.u64(static_cast<std::uint64_t>(cols));
    w.u64(filters);
    std::array<std::uint8_t, kColourPeriod * kColourPeriod> colour{};
    if (filters)
        for (int r = 0; r < kColourPeriod; ++r)
            for (int c = 0; c < kColourPeriod; ++c)
                colour[static_cast<std::size_t>(r * kColourPeriod + c)] =
                    static_cast<std::uint8_t>(raw->COLOR(r, c));
    w.bytes(colour.data(), colour.size());
    w.f64(C.black);
    w.f64(C.maximum);
    static_assert(sizeof C.cblack == sizeof(RawFrame::cblack));
    w.bytes(C.cblack, sizeof C.cblack);
    w.str(std::string(raw->imgdata.idata.make) + " " + raw->imgdata.idata.model);
    const std::size_t pitch = S.raw_pitch / 2;
    for (long long r = 0; r < rows; ++r)
        w.bytes(R.raw_image + static_cast<std::size_t>(r + S.top_margin) * pitch + S.left_margin,
                sizeof(std::uint16_t) * static_cast<std::size_t>(cols));
}

// In the caller: reads the frame, checking every size before allocating.
RawFrame receive_frame(const fs::path& path, IsolatedReader& in) {
    RawFrame f;
    const std::uint64_t rows = in.u64(), cols = in.u64();
    if (rows < 1 || cols < 1 || rows > std::uint64_t(kMaxImageSamples) ||
        cols > std::uint64_t(kMaxImageSamples))
        throw bad_raw(path, "the RAW reader's process sent an impossible size");
    // The samples (2 bytes each) beside the doubles extract() makes.
    f.samples_charge =
        detail::check_image_size(path, static_cast<long long>(rows), static_cast<long long>(cols),
                                 1, 2.0 * double(rows) * double(cols));
    f.rows = static_cast<int>(rows);
    f.cols = static_cast<int>(cols);
    f.filters = static_cast<unsigned>(in.u64());
    in.bytes(f.colour.data(), f.colour.size());
    f.black = in.f64();
    f.maximum = in.f64();
    in.bytes(f.cblack.data(), sizeof f.cblack);
    f.camera = in.str(kMaxCameraName);
    f.samples.resize(static_cast<std::size_t>(rows * cols));
    in.bytes(f.samples.data(), sizeof(std::uint16_t) * f.samples.size());
    return f;
}

// The documented interpretation of a frame (see raw_io.hpp).
LoadedImage extract(const fs::path& path, const RawFrame& f, BayerMode mode, RawInfo& info) {
    const int rows = f.rows, cols = f.cols;
    const auto& cb = f.cblack;
    auto black_at = [&](int r, int c, int colour) {
        double b = f.black + (colour >= 0 && colour < 4 ? cb[static_cast<std::size_t>(colour)] : 0);
        if (cb[4] && cb[5]) {
            const std::size_t k =
                6 + (unsigned(r) % cb[4]) * std::size_t(cb[5]) + (unsigned(c) % cb[5]);
            if (k < LIBRAW_CBLACK_SIZE) b += cb[k];
        }
        return b;
    };
    auto value = [&](int r, int c) {
        const int colour = f.filters ? f.colour_at(r, c) : 0;
        return double(f.samples[static_cast<std::size_t>(r) * static_cast<std::size_t>(cols) +
                                static_cast<std::size_t>(c)]) -
               black_at(r, c, colour);
    };
    info.camera = f.camera;
    info.black = f.black;
    info.white = f.maximum;
    const double span = f.maximum - f.black;
    if (!(span > 0)) throw bad_raw(path, "white level not above the black level");
    LoadedImage out;
    out.format = SampleFormat::kUint16;
    if (!f.filters) {
        out.image = Image(rows, cols, 1);
        Plane& p = out.image.channels[0];
        for (int r = 0; r < rows; ++r)
            for (int c = 0; c < cols; ++c) p(r, c) = value(r, c);
        out.full_scale = span;
        info.note = "monochrome RAW: full resolution, " + field_ref("bayer") + " does not apply";
        return out;
    }
    // The 2 x 2 CFA of the first block must hold R, B and two G (colours 1 and 3 are green).
    std::array<int, 4> count{};
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) ++count[static_cast<std::size_t>(f.colour_at(r, c) & 3)];
    if (count[0] != 1 || count[2] != 1 || count[1] + count[3] != 2)
        throw bad_raw(path, "the CFA is not a 2 x 2 Bayer pattern (RGGB, BGGR, GRBG, GBRG)");
    if (rows < 2 || cols < 2) throw bad_raw(path, "smaller than one 2 x 2 Bayer block");
    const int hr = rows / 2, hc = cols / 2;
    out.image = Image(hr, hc, 1);
    Plane& p = out.image.channels[0];
    for (int r = 0; r < hr; ++r)
        for (int c = 0; c < hc; ++c) {
            double sum = 0, green = 0, red = 0, blue = 0;
            for (int a = 0; a < 2; ++a)
                for (int b = 0; b < 2; ++b) {
                    const int rr = 2 * r + a, cc = 2 * c + b;
                    const double v = value(rr, cc);
                    const int colour = f.colour_at(rr, cc);
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
    out.full_scale = mode == BayerMode::kSum2x2 ? 4 * span : span;
    info.binning = 2;
    info.bayer = bayer_mode_name(mode);
    info.note = "Bayer RAW read as " + info.bayer + ": " + std::to_string(hc) + " x " +
                std::to_string(hr) +
                " px, one pixel per 2 x 2 block: the pixel pitch is "
                "twice the sensor's";
    return out;
}

}  // namespace

LoadedImage read_raw(const fs::path& path, BayerMode mode, RawInfo* info_out) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) throw bad_raw(path, "file does not exist");
    if (fs::file_size(path, ec) == 0) throw bad_raw(path, "file is empty");
    RawFrame frame;
    try {
        run_isolated([&](IsolatedWriter& w) { send_frame(path, w); },
                     [&](IsolatedReader& r) { frame = receive_frame(path, r); });
    } catch (const IsolatedCrash& e) {
        throw bad_raw(path, std::string("LibRaw crashed reading this file (") + e.what() +
                                "); the file is refused. LibRaw runs in a separate process, so "
                                "only that process ended");
    }
    RawInfo info;
    LoadedImage out = extract(path, frame, mode, info);
    if (info_out) *info_out = info;
    return out;
}

LoadedImage read_capture(const fs::path& path, BayerMode mode, RawInfo* info) {
    if (is_raw_extension(path)) return read_raw(path, mode, info);
    if (info) *info = RawInfo{};
    return read_image(path);
}

}  // namespace pinmask
