#include "cli/options/export_options.hpp"

#include "cli/options/flag_names.hpp"
#include "io/export_sidecar_of.hpp"

namespace pinmask::cli {

io::ExportSidecar export_sidecar_of(const ExportFlags& f, const Mask& mask, const ExportOptions& o,
                                    const ExportSummary& s) {
    io::ExportSidecar d = io::export_sidecar_of(f, mask, o, s);
    for (std::string& n : d.notes) n = spell_flags(n);
    return d;
}

}  // namespace pinmask::cli
