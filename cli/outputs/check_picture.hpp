// `pinmask check` of a picture export wrote (PDF, PNG, 1-bit TIFF): the design is rebuilt from
// the mask and the export sidecar (or --mask and the flags; a PNG needs the sidecar for its
// dpi) and the picture compared with it (export/pipeline/file_check check_picture_file).
#pragma once

#include "cli/options/check_settings.hpp"
#include "cli/outputs/check_report.hpp"
#include "export/layout/vendor_rules.hpp"
#include "export/pipeline/file_check.hpp"

namespace pinmask::cli {

// Fills rep.settings, rep.mask and rep.rules. Throws InvalidInput when no mask is known.
FileCheck check_picture(const CheckOptions& o, const VendorRules& vendor, CheckReport& rep);

}  // namespace pinmask::cli
