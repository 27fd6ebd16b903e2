// Scene names and dispatch, plus the geometric scenes (point, checker, Siemens star, USAF).
// The letter, natural texture and file scenes live in scene_letter.cpp, scene_natural.cpp and
// scene_file.cpp.
#include "optimize/simulate/scenes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/errors/error.hpp"
#include "core/files/input_file.hpp"

namespace pinmask {
namespace {

void check_size(int rows, int cols) {
    if (rows < 1 || cols < 1) {
        throw InvalidInput("scene size " + std::to_string(rows) + " x " + std::to_string(cols) +
                           ": both dimensions must be >= 1");
    }
}

// Length of [a0, a1) inside pixel [p, p + 1).
double overlap(double a0, double a1, double p) {
    return std::max(0.0, std::min(a1, p + 1.0) - std::max(a0, p));
}

// Adds `value` times the exact pixel coverage of the rectangle [y0, y1) x [x0, x1) (pixels).
void add_rect(Plane& img, double y0, double y1, double x0, double x1, double value) {
    const int r0 = std::max(0, static_cast<int>(std::floor(y0)));
    const int r1 = std::min(static_cast<int>(img.rows()) - 1, static_cast<int>(std::ceil(y1)));
    const int c0 = std::max(0, static_cast<int>(std::floor(x0)));
    const int c1 = std::min(static_cast<int>(img.cols()) - 1, static_cast<int>(std::ceil(x1)));
    for (int r = r0; r <= r1; ++r) {
        const double oy = overlap(y0, y1, r);
        if (oy <= 0.0) continue;
        for (int c = c0; c <= c1; ++c) img(r, c) += value * oy * overlap(x0, x1, c);
    }
}

// Antiderivative of the +-1 square wave of half-period s (+1 on [0, s)): a triangle wave.
double square_wave_integral(double x, double s) {
    const double t = x - 2.0 * s * std::floor(x / (2.0 * s));
    return t < s ? t : 2.0 * s - t;
}

}  // namespace

const std::vector<std::string>& builtin_scene_names() {
    static const std::vector<std::string> names{"letter-R", "usaf",  "siemens-star",
                                                "checker",  "point", "natural"};
    return names;
}

SceneSpec scene_from_name(const std::string& name) {
    SceneSpec s;
    if (name == "letter-R") {
        s.kind = SceneKind::kLetterR;
    } else if (name == "usaf") {
        s.kind = SceneKind::kUsaf;
    } else if (name == "siemens-star") {
        s.kind = SceneKind::kSiemensStar;
    } else if (name == "checker") {
        s.kind = SceneKind::kChecker;
    } else if (name == "point") {
        s.kind = SceneKind::kPoint;
    } else if (name == "natural") {
        s.kind = SceneKind::kNatural;
    } else {
        std::error_code ec;
        // A name that exists but is no regular file (a pipe would block the read, a device
        // never ends) is refused by what it is, as every reader refuses it.
        if (!name.empty() && std::filesystem::exists(name, ec)) {
            if (const auto problem = input_file_problem(name))
                throw invalid_field("scene", "'" + name + "'", *problem);
        }
        if (name.empty() || !std::filesystem::is_regular_file(name, ec)) {
            std::string list;
            for (const auto& n : builtin_scene_names()) list += (list.empty() ? "" : ", ") + n;
            throw invalid_field("scene", "'" + name + "'",
                                "must be a built-in scene (" + list + ") or an existing file");
        }
        s.kind = SceneKind::kFile;
        s.path = name;
    }
    return s;
}

std::string scene_name(const SceneSpec& spec) {
    switch (spec.kind) {
        case SceneKind::kLetterR:
            return "letter-R";
        case SceneKind::kUsaf:
            return "usaf";
        case SceneKind::kSiemensStar:
            return "siemens-star";
        case SceneKind::kChecker:
            return "checker";
        case SceneKind::kPoint:
            return "point";
        case SceneKind::kNatural:
            return "natural";
        case SceneKind::kFile:
            return spec.path.string();
    }
    return "?";
}

Image make_scene(const SceneSpec& spec, int rows, int cols) {
    check_size(rows, cols);
    switch (spec.kind) {
        case SceneKind::kLetterR:
            return Image(letter_r_scene(rows, cols));
        case SceneKind::kUsaf:
            return Image(usaf_scene(rows, cols));
        case SceneKind::kSiemensStar:
            return Image(siemens_star_scene(rows, cols, spec.star_spokes));
        case SceneKind::kChecker:
            return Image(checker_scene(rows, cols, spec.checker_squares));
        case SceneKind::kPoint:
            return Image(point_scene(rows, cols));
        case SceneKind::kNatural:
            return Image(natural_scene(rows, cols, spec.seed, spec.alpha));
        case SceneKind::kFile:
            return file_scene(spec.path, rows, cols);
    }
    throw InvalidInput("scene: unknown kind");
}

Plane point_scene(int rows, int cols) {
    check_size(rows, cols);
    Plane p = Plane::Zero(rows, cols);
    p(rows / 2, cols / 2) = 1.0;
    return p;
}

Plane checker_scene(int rows, int cols, int squares) {
    check_size(rows, cols);
    if (squares < 1) {
        throw invalid_field("checker_squares", std::to_string(squares), "must be >= 1");
    }
    const double s = static_cast<double>(std::min(rows, cols)) / squares;
    // The pixel average of (1 + f(x) f(y)) / 2 with f the +-1 square wave factorises.
    auto averages = [s](int count) {
        Eigen::ArrayXd a(count);
        for (int i = 0; i < count; ++i) {
            a(i) = square_wave_integral(i + 1.0, s) - square_wave_integral(i, s);
        }
        return a;
    };
    const Eigen::ArrayXd ay = averages(rows), ax = averages(cols);
    Plane p(rows, cols);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) p(r, c) = 0.5 * (1.0 + ay(r) * ax(c));
    return p;
}

Plane siemens_star_scene(int rows, int cols, int spokes) {
    check_size(rows, cols);
    if (spokes < 1) throw invalid_field("star_spokes", std::to_string(spokes), "must be >= 1");
    const double cy = rows / 2.0, cx = cols / 2.0;
    const double radius = 0.45 * std::min(rows, cols);
    const int m = kStarSupersample;
    const double sector = std::numbers::pi / spokes;  // angular width of one sector
    const double half_diagonal =
        std::numbers::sqrt2 / 2.0;  // a pixel lies within this of its centre
    auto value_at = [&](double y, double x) {
        if (x * x + y * y > radius * radius) return 0.0;
        return std::sin(spokes * std::atan2(y, x)) > 0.0 ? 1.0 : 0.0;
    };
    Plane p(rows, cols);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const double y = r + 0.5 - cy, x = c + 0.5 - cx;
            // A pixel farther than half a diagonal from every sector edge (a ray from the
            // centre) and from the rim is uniform: one sample is exact. Others are supersampled.
            const double rho = std::hypot(x, y);
            const double theta = std::atan2(y, x);
            const double to_edge = std::fabs(theta / sector - std::round(theta / sector)) * sector;
            const bool uniform =
                std::fabs(rho - radius) > half_diagonal &&
                rho * std::sin(std::min(to_edge, std::numbers::pi / 2)) > half_diagonal;
            if (uniform) {
                p(r, c) = value_at(y, x);
                continue;
            }
            double sum = 0.0;
            for (int i = 0; i < m; ++i)
                for (int j = 0; j < m; ++j)
                    sum += value_at(r + (i + 0.5) / m - cy, c + (j + 0.5) / m - cx);
            p(r, c) = sum / (m * m);
        }
    return p;
}

Plane usaf_scene(int rows, int cols) {
    check_size(rows, cols);
    constexpr double kFirstBar = 0.06;   // bar width of the first element, frame fraction
    constexpr double kLastBar = 0.0025;  // stop below this bar width
    constexpr double kStep = std::numbers::sqrt2 / 2.0;  // bar width ratio between elements
    constexpr double kMargin = 0.04;                     // empty frame border, frame fraction
    Plane p = Plane::Zero(rows, cols);
    // Layout in frame fractions (u across, v down), drawn in pixels.
    auto bar = [&](double v0, double v1, double u0, double u1) {
        add_rect(p, v0 * rows, v1 * rows, u0 * cols, u1 * cols, 1.0);
    };
    double u = kMargin, v = kMargin, shelf = 0.0;
    for (double w = kFirstBar; w >= kLastBar; w *= kStep) {
        const double width = 11.0 * w, height = 5.0 * w;
        if (u + width > 1.0 - kMargin) {  // next shelf
            u = kMargin;
            v += shelf + 2.0 * w;
            shelf = 0.0;
        }
        if (v + height > 1.0 - kMargin) break;
        for (int b = 0; b < 3; ++b) {
            bar(v, v + height, u + 2.0 * b * w, u + (2.0 * b + 1.0) * w);           // vertical bars
            bar(v + 2.0 * b * w, v + (2.0 * b + 1.0) * w, u + 6.0 * w, u + width);  // horizontal
        }
        u += width + 2.0 * w;
        shelf = std::max(shelf, height);
    }
    return p.min(1.0);
}

}  // namespace pinmask
