// Process limits of the places a mask can be made, as presets for the design-rule check
// (export/pipeline/drc). Lengths in integer nanometres, like export/layout/layout.hpp.
//   film    laser film plotter at 20 000 dpi (1.27 um address): clear features and opaque gaps
//           of at least 16 um, i.e. about 12 plotter pixels, the usual film-shop minimum.
//   chrome  e-beam/laser-written chrome on glass: features and gaps of at least 1 um.
//   none    no process limits: only the geometric rules (closed, simple, CCW, disjoint, inside
//           the area, vertex limit); give explicit limits on top of it (`--min-gap` etc.).
// Every preset keeps polygons at the GDS-friendly 199-vertex limit (200 points with the
// closing point), which every GDSII consumer accepts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace pinmask {

// GDSII XY records: 200 points (199 vertices + closing point) is the classic limit every tool
// accepts; 8191 points (8190 vertices) is the hard limit of the 16-bit record length.
inline constexpr std::size_t kGdsFriendlyMaxVertices = 199;
inline constexpr std::size_t kGdsHardMaxVertices = 8190;

struct VendorRules {
    std::string name;
    std::string description;
    std::int64_t min_feature_nm = 0;  // narrowest drawn (tone) polygon
    std::int64_t min_gap_nm = 1;      // closest approach of two polygons (1 nm: must not touch)
    std::size_t max_vertices = kGdsFriendlyMaxVertices;
};

// Names of the presets, in the order they are listed in messages: film, chrome, none.
std::vector<std::string> vendor_names();

// The preset called `name`; an unknown name throws InvalidInput listing the known ones.
VendorRules vendor_rules(std::string_view name);

}  // namespace pinmask
