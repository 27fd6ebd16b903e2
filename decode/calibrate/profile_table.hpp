// The pixel-integrated 1-D profile of one square pinhole of side d on the sensor, tabulated for
// the forward-model fit (decode/calibrate/forward_fit). Notation as design/psf/kernel_profile.hpp;
// x is the sensor coordinate in pixels from the spot centre.
//   box         density 1/W on |x| < W/2, W = |M(u)| d / w (the geometric spot);
//   fraunhofer  density a sinc^2(a x), a = d w / (lambda f) (v per pixel);
//   fresnel     density a h(N, a x), N = d^2 |1/z_eff(u)| / (4 lambda) (design/psf/kernel_profile).
// The value a pixel records, q(x) = int_{x-1/2}^{x+1/2} density, is H(x + 1/2) - H(x - 1/2)
// with H the cumulative density (trapezoid sums of the density on a fine grid, or the box's
// closed form); a square pinhole's pixel value at offsets (u, v) along the mask's axes is
// q(u) q(v) (exact without rotation; for rotations of a few degrees the pixel's own rotation
// against the spot's axes is neglected). Tabulated on x in [-half, half] at `step` pixels, read
// by linear interpolation; q is 0 outside.
#pragma once

#include <vector>

#include "design/optics/camera.hpp"
#include "design/psf/kernel_model.hpp"

namespace pinmask::calibrate {

class ProfileTable {
  public:
    ProfileTable() = default;
    // `family` box, fraunhofer or fresnel; `side_m` the pinhole side d; `half_px` the half width
    // of the table (pixels). Throws InvalidInput for another family or a non-positive side.
    ProfileTable(const Camera& camera, KernelModel family, double side_m, double half_px);

    double half_px() const { return half_; }
    // q(x) and its derivative dq/dx (linear interpolation of q; the slope of the segment).
    // Inline: the forward fit reads them for every pixel of every spot's window.
    double value(double x) const {
        const double t = (x + half_) * inv_step_;
        if (t < 0 || t >= double(q_.size() - 1)) return 0.0;
        const auto k = static_cast<std::size_t>(t);
        const double f = t - double(k);
        return q_[k] + f * (q_[k + 1] - q_[k]);
    }
    void value_slope(double x, double& q, double& dq) const {
        const double t = (x + half_) * inv_step_;
        if (t < 0 || t >= double(q_.size() - 1)) {
            q = dq = 0.0;
            return;
        }
        const auto k = static_cast<std::size_t>(t);
        const double f = t - double(k);
        q = q_[k] + f * (q_[k + 1] - q_[k]);
        dq = (q_[k + 1] - q_[k]) * inv_step_;
    }
    // The side derivative's two tables on one grid: q of this table and of `other` (same half
    // width and step, e.g. another side) at x with one index computation, and this table's slope.
    void value_slope_pair(const ProfileTable& other, double x, double& q, double& dq,
                          double& q_other) const {
        const double t = (x + half_) * inv_step_;
        if (t < 0 || t >= double(q_.size() - 1)) {
            q = dq = q_other = 0.0;
            return;
        }
        const auto k = static_cast<std::size_t>(t);
        const double f = t - double(k);
        q = q_[k] + f * (q_[k + 1] - q_[k]);
        dq = (q_[k + 1] - q_[k]) * inv_step_;
        q_other = other.q_[k] + f * (other.q_[k + 1] - other.q_[k]);
    }
    bool same_grid(const ProfileTable& other) const {
        return q_.size() == other.q_.size() && half_ == other.half_ && step_ == other.step_;
    }
    // Fraction of the profile's energy inside [-half - 1/2, half + 1/2] (1 for a box that fits).
    double enclosed() const { return enclosed_; }

  private:
    std::vector<double> q_;
    double half_ = 0.0, step_ = 1.0, inv_step_ = 1.0, enclosed_ = 1.0;
};

// The family the fit uses for a mask's kernel model: box, fraunhofer and fresnel as they are;
// auto by design/psf/kernel_model's rule at the camera's Fresnel number; the paper's table and a
// measured kernel (no side to vary) by that rule too.
KernelModel fit_family(const Camera& camera, KernelModel model);

// Half width (pixels) holding the profile's energy up to `energy` per axis (box: its half side
// plus one pixel), at most `cap_px`.
double profile_support_px(const Camera& camera, KernelModel family, double side_m, double energy,
                          double cap_px);

}  // namespace pinmask::calibrate
