// Text helpers of the report library (internal): number formatting for
// tables, CSV fields, and quoting for gnuplot scripts and the shell.
#pragma once

#include <string>

namespace layers::report {

// `v` with `digits` decimals; "" for a non-finite value (an empty CSV cell).
std::string fixed(double v, int digits);
// The same with a sign (+1.25, -0.50); "" when not finite.
std::string signed_fixed(double v, int digits);
// Shortest round-trip-ish form for machine tables ("" when non-finite).
std::string exact(double v);
// A share 0..1 as a percentage with two decimals ("-" when non-finite).
std::string percent(double share);
// `mean +- std` with one decimal ("-" when the mean is non-finite).
std::string mean_pm_std(double mean, double std);
// A CSV field: quoted when it holds a comma, quote or newline.
std::string csv_field(const std::string& s);
// A single-quoted gnuplot string literal (quotes doubled).
std::string gnuplot_string(const std::string& s);
// A single-quoted POSIX shell word.
std::string shell_word(const std::string& s);
// A Markdown table cell: '|' escaped, newlines as spaces.
std::string md_cell(const std::string& s);

}  // namespace layers::report
