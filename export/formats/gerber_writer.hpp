// Gerber X2 (RS-274X) image of a layout: millimetres (%MOMM*%), format 4.6 with leading zeros
// omitted and absolute coordinates (%FSLAX46Y46*%), so a coordinate is the layout's integer
// nanometres written as an integer (1e-6 mm = 1 nm). Each ring is one G36/G37 region (D02 to the
// first vertex, D01 to every other vertex and back to the first). File attributes:
// .GenerationSoftware, .FileFunction (Other,Photomask), .FilePolarity: Negative in clear tone
// (the regions are where the chrome is absent) and Positive in dark tone (the regions are the
// chrome). G04 comments state the units, tone, mirroring and mask hash (export/layout/geometry
// layout_info). Ends with M02. Deterministic.
#pragma once

#include <string>

#include "export/layout/layout.hpp"

namespace pinmask {

// The .FilePolarity attribute of a tone: "Negative" for clear (the regions are where the chrome
// is absent), "Positive" for dark (the regions are the chrome).
std::string gerber_file_polarity(Tone tone);

// The complete file. Throws InvalidInput for a coordinate beyond the 4.6 format (|x| >= 10 m).
// native_circles: round pinholes (layout.circles non-empty) as flashes of one circular aperture
// (%ADD10C,<diameter mm>*%, D10, X..Y..D03) instead of regions.
std::string gerber_document(const Layout& layout, bool native_circles = false);

}  // namespace pinmask
