// zhf bench's plots, drawn by gnuplot from one CSV: the Pareto front of every order (the methods
// that no other method beats on both time and error, one vector per call), each method's fastest
// path per order in one panel per scenario, and time against order. The CSV's columns are order,
// ns_median, max_error and a label last, so no label can shift a numeric column.
#pragma once

#include <string>

#include "zhf/bench/suite.h"

namespace zhf::io {
class PendingFiles;
}

namespace zhf::bench {

// Least-squares slope of log(ns) against log(N) for one method and scenario (orders >= 3).
double scaling_exponent(const SuiteReport& report, const std::string& method, const std::string& scenario,
                        const std::string& variant = "");

// Refuses (OutputError) a --plot path stage_plots could not use: control characters in it, a file
// beside it (FILE.csv, FILE.gp, FILE_scenarios.svg, FILE_scaling.svg) that zhf bench did not write,
// or no gnuplot to draw with. Call it before measuring.
void check_plot_targets(const std::string& svg_path);

// Draws svg_path (the Pareto fronts), FILE_scenarios.svg and FILE_scaling.svg, with FILE.csv and
// FILE.gp beside them (the script redraws the plots: gnuplot FILE.gp), staged in outputs for the
// caller to commit with its other outputs (all or nothing). Returns what they hold, for the
// message after the commit. Throws OutputError when gnuplot fails.
std::string stage_plots(const SuiteReport& report, const std::string& svg_path, io::PendingFiles& outputs);

}  // namespace zhf::bench
