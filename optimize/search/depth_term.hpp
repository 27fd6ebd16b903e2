// The depth term of the search objective (`search --depth-weight W`): W x D(pattern), where
//   D = 20 log10( max_k sigma_u(u_k) / u_k )  dB,  sigma_u(u) = u^2 / sqrt(I(1/u)),
// the worst relative Cramer-Rao bound on the distance of a point source on the axis over the
// distances u_k of optimize/metrics/depth_fisher's DepthRange (score's depth_crb_rel, in dB).
// Better depth discrimination makes D lower, so a positive W trades image quality for depth
// resolution. D is negative for any usable mask; only its changes matter to the search.
//
// Evaluated millions of times, the Fisher information is taken as additive over the pinholes:
//   I_k(pattern) = sum over open cells c of I_k(c),
// I_k(c) the information the spots of cell c (one per tile) carry alone: the exact-geometry PSF
// (design/psf/psf_exact) and its derivative in 1/u rendered once per u_k for the cells of each
// residue class (row mod 2, col mod 2), whose spots are two pitches apart, each pixel's term
// (d mu)^2 / (mu + read^2) given to the cell of the nearest spot. Each spot carries
// photons_per_pinhole electrons (depth_fisher_noise: photons = photons_per_pinhole K, each
// pinhole 1/K of them), so I_k(c) does not depend on K. The sum is exact when no two open
// spots share a pixel; neighbouring spots' shared pixels and overlapping diffraction tails make
// it an approximation, measured against depth_fisher in docs/depth.md.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "design/pattern/mask.hpp"
#include "optimize/metrics/depth_fisher.hpp"
#include "optimize/search/search.hpp"
#include "optimize/simulate/noise_model.hpp"

namespace pinmask {

class DepthCellTable {
  public:
    // `tmpl`: camera, PSF settings, pattern n and tiles (its pinholes are not used). `noise`
    // must be the photon model (InvalidInput naming `weights.depth` otherwise).
    // `threads` renderings at a time (the result does not depend on it: each cell's entry comes
    // from one rendering).
    DepthCellTable(const Mask& tmpl, const NoiseModel& noise, const DepthRange& range,
                   int threads = 1);

    // The worst relative bound max_k sigma_u(u_k) / u_k of a pattern's open cells (+inf
    // without any information).
    double crb_rel(const std::vector<Cell>& pinholes) const;
    const std::vector<double>& distances_m() const { return u_; }
    // I_k(c) in m^2 (row-major n x n per distance).
    const std::vector<std::vector<double>>& cell_information() const { return info_; }

  private:
    int n_ = 0;
    std::vector<double> u_;
    std::vector<std::vector<double>> info_;
};

// inner's objective plus weight x D. Terms add "depth_crb_rel" (the ratio) and
// "depth_crb_rel_db" (D), and "objective" becomes the sum.
class DepthTermObjective : public SearchObjective {
  public:
    DepthTermObjective(std::unique_ptr<SearchObjective> inner,
                       std::shared_ptr<const DepthCellTable> table, double weight);
    double evaluate(const PatternState& state) const override;
    std::map<std::string, double> terms(const PatternState& state) const override;

  private:
    double depth_db(const PatternState& state) const;

    std::unique_ptr<SearchObjective> inner_;
    std::shared_ptr<const DepthCellTable> table_;
    double weight_ = 0;
};

}  // namespace pinmask
