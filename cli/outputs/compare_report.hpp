// `pinmask compare`'s text rendering of its table (its JSON is io/compare_json's, the report data
// report/compare_report.hpp's).
#pragma once

#include <string>

#include "optimize/metrics/compare.hpp"
#include "report/compare_report.hpp"
#include "report/report.hpp"

namespace pinmask::cli {

using pinmask::compare_document;
using pinmask::compare_table;
using pinmask::CompareSummary;
using pinmask::noise_caption;

// The table as aligned text for stdout, with a legend line.
std::string compare_table_text(const ReportTable& table);

using pinmask::compare_holes_text;

}  // namespace pinmask::cli
