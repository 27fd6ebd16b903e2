// `pinmask compare`'s text and JSON renderings of its results (the report data itself is
// report/compare_report.hpp's).
#pragma once

#include <nlohmann/json.hpp>
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

// One row as JSON (compare --json and the report config): the table figures plus every noise
// level under score's keys.
nlohmann::ordered_json compare_row_json(const CompareRow& row);

}  // namespace pinmask::cli
