// What identifies the film in a fabrication file, compared with what the export wrote: a mask
// shop images the layer (GDSII/OASIS layer and datatype, a DXF layer name) it is told to, and a
// Gerber plotter exposes by the file's polarity; geometry on another layer or a flipped polarity
// makes a different film from identical polygons. `pinmask check` and Python's check() run this
// beside the design-rule check (export/pipeline/file_check): a mismatch fails the check like a
// violation; what nothing says the file should be is listed as not known, never as clean.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "export/formats/read_any.hpp"
#include "export/layout/layout.hpp"
#include "export/layout/rings.hpp"

namespace pinmask {

// What the file should be, as far as anything says (io/sidecar_identity builds it from the
// export sidecar and the vendor preset).
struct FilmIdentityExpected {
    std::optional<std::string> layer;  // GDSII/OASIS "layer/datatype", DXF layer name
    std::string layer_source;          // where `layer` comes from, or why it is not known
    std::optional<Tone> tone;          // Gerber: the polarity of this tone
    std::string tone_source;           // where `tone` comes from, or why it is not known
};

struct FilmIdentityItem {
    std::string what;      // "GDSII layer/datatype", "DXF layer", "Gerber polarity"
    std::string found;     // as the file has it ("1/0", "PINMASK", "Negative"; "none")
    std::string expected;  // "" when not known
    std::string source;    // where the expectation comes from, or why it is not known
    bool ok = true;        // false: a mismatch (the check fails)
    std::string message;   // one line for people
};

struct FilmIdentity {
    std::vector<FilmIdentityItem> items;
    bool ok() const;
    // The items whose expectation is not known (compared with nothing).
    std::vector<const FilmIdentityItem*> not_known() const;
};

// Compares `file` (read as `format`) with `expected`:
//   GDSII, OASIS, DXF: geometry on more than one layer is a mismatch whatever is expected (a
//     film is one layer: the shop images only the one it is told); one layer other than the
//     expected one is a mismatch; with no expectation the layer is reported as not known.
//   Gerber: the .FilePolarity attribute against the expected tone's (Negative for clear,
//     Positive for dark), and against the tone the file's own pinmask comment states; a file
//     without the attribute when a polarity is expected is a mismatch.
//   SVG: nothing identifies the film beyond its drawing (no items).
FilmIdentity check_film_identity(const FileGeometry& file, FabFormat format,
                                 const FilmIdentityExpected& expected);

}  // namespace pinmask
