// The data-consistency cost of one candidate object distance u (one plane of the sweep).
//
// The cue (docs/depth.md): a scene point at distance u lands through pinhole s at M(u) s on the
// sensor (Eq. (3), M(u) = 1 - f/f' + f/u), so each distance has its own PSF h_u, a pattern whose
// scale follows 1/u. The Wiener estimate at u, x_u = G_u p with G_u = conj(H_u) / (|H_u|^2 + nsr)
// (scalar NSR, deconvwnr convention, cyclic over the capture, PSF normalised to sum 1), explains
// the part of the capture that h_u can produce; the residual
//   r_u = p - h_u (*) x_u = ifft(nsr / (|H_u|^2 + nsr) P)
// keeps the capture's energy at the frequencies where H_u is weak. Light from another distance
// carries the spectrum of another pattern scale, so it leaves more residual: the cost of plane u
// is the local energy of r_u, the box mean of r_u^2 over window x window pixels (cyclic). Its
// frame mean is the data term of the Gaussian evidence of u (the capture's energy weighted by
// nsr / (|H_u|^2 + nsr)).
// Locality: light from one scene point spreads over the whole PSF (the tiled mask's image, a few
// hundred pixels), so the residual of a region spreads as far; the cost map resolves depth only
// on regions of about that size (the measured figures are in docs/depth.md).
// The estimate x_u is returned too: the all-in-focus image takes each pixel from its plane.
// Evidence (docs/depth.md section 3b): minus twice the log marginal likelihood of the whole
// capture under plane u, per pixel, with a Gaussian scene prior S(f) = A / (lambda(f) + eps)
// (lambda the cyclic discrete Laplacian's eigenvalue 4 sin^2(pi k/R) + 4 sin^2(pi l/C), the
// 1/f^2 law; eps = 1e-4) and white noise s^2: with P(f) = |Y(f)|^2 / N and
// D_u(f) = |H_u(f)|^2 S(f) + s^2, evidence = mean_f [P / D_u + log D_u]. s^2 is the mean of P
// where lambda > 6 (near Nyquist), A = max(sum_f P - s^2 N, 1e-12) / sum_f |H_u|^2 / (lambda +
// eps) (the capture's power matched by plane u's model). Lower is better; unlike the residual
// energy it charges a model for the captures it could have explained (the log D term).
#pragma once

#include "core/image/image.hpp"
#include "design/pattern/mask.hpp"

namespace pinmask {

struct PlaneCost {
    Plane cost;           // capture's size, in [0, 2]
    Plane estimate;       // Wiener decode of the whole capture with the full exact PSF at u
    double evidence = 0;  // of the whole capture (above); any sign
};

// capture: rows x cols (>= 8 each, finite); window odd, >= 3, at most the smaller side;
// nsr > 0. Throws InvalidInput naming the field.
PlaneCost sweep_cost(const Plane& capture, const Mask& mask, double object_distance_m, double nsr,
                     int window);

// The same cost for a given PSF of the plane (a measured or externally computed one): at most
// the capture's size in each dimension, zero-padded and centred as decode/solvers/psf2otf does
// (deconvwnr convention), non-negative with a positive sum (normalised here to sum 1).
PlaneCost sweep_cost(const Plane& capture, const Plane& psf, double nsr, int window);

// The cyclic box mean of p over a window x window box centred on each pixel (window odd).
Plane box_mean(const Plane& p, int window);

}  // namespace pinmask
