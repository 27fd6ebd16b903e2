// The start of the forward fit (decode/calibrate/forward_fit) from the capture's Fourier transform,
// not from spots: spots one cell wide or more run together, and a lattice through their centroids
// lands a cell off or at the wrong pitch.
// Coordinates and lattice as decode/calibrate/forward_fit.hpp (index coordinates, rotation
// counter-clockwise on screen with rows running down, pitches along the mask's column and row
// axes).
//
// 1. Pitch and rotation from the power spectrum. The spots sit on the cell lattice A (C, R) + x0,
//    A = [[px cos t, py sin t], [-px sin t, py cos t]], with the design's n x n pattern repeated:
//    the capture's spectrum is the kernel's transfer function times a comb on the reciprocal
//    lattice f_m = A^-T m / n (m integer), whose peak at m has the weight |P(m mod n)|^2 (P the
//    pattern's DFT, independent of where the mask sits). The score of a lattice is the sum of
//    these weights times the whitened power spectrum (Hann window, divided by its mean over rings
//    of equal |f|, so every ring counts alike) sampled at f_m, over the frequencies that rise
//    above the noise floor. It is maximised coarse to fine: first over the whole searched range
//    (+- max rotation, pitch +- pitch_range) with the low frequencies only, then the band is
//    doubled and the step halved around the best point (a step moves the highest harmonic used
//    by 0.4 frequency bins), down to the highest usable frequency.
// 2. The lattice refined by the sharpness of the capture folded onto one period (each pixel's
//    lattice coordinates modulo n, binned at q bins per cell and averaged): the peak of the
//    fold's cyclic cross-correlation (FFT) with the pattern's open cells, over a 3 x 3 x 3 grid
//    of rotation and pitches around the best point with the step halved each time (a wrong pitch
//    or rotation smears the periods over each other).
// 3. Position modulo one period: that correlation's peak for the fold of every pixel, refined by
//    a parabola, is the lattice coordinate of cell (0, 0) modulo n.
// 4. Which period: each placement of the whole tiled mask differing by whole periods is scored by
//    the capture's values at its in-frame spot sites, less half the median value at the sites of
//    the placement with the most of them (a site on an empty part of the frame costs, a site on a
//    spot gains). Placements with the same sites tie; the one whose mask centre is nearest the
//    frame's centre is kept.
#pragma once

#include "core/image/image.hpp"
#include "decode/calibrate/forward_fit.hpp"
#include "design/pattern/pattern.hpp"

namespace pinmask::calibrate {

struct FftStartOptions {
    double nominal_pitch_px = 0.0;  // the design's pixels per cell in capture pixels (> 0)
    double pitch_range = 0.05;      // pitches searched: nominal +- this fraction
    double max_rotation_deg = 5.0;  // rotations searched: +- this
};

struct FftStart {
    LatticeStart lattice;
    // Highest spatial frequency used (cycles per pixel) and the whitened comb score there
    // (1 for a spectrum with no comb; the spots' comb makes it larger).
    double max_frequency = 0.0;
    double score = 0.0;
};

// Throws InvalidInput when the frame is smaller than 8 x 8 pixels or the pattern has no open cell.
FftStart fft_lattice_start(const Plane& frame, const Pattern& pattern,
                           const FftStartOptions& options);

}  // namespace pinmask::calibrate
