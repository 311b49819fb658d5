// SH coefficient vectors from a file, as zhf analyze (and anything else taking user
// coefficients) reads them. Two layouts, told apart by the first character:
//  - JSON: an array of vectors. A vector is an array of N^2 numbers (one channel) or an
//    array of C such arrays (C channels, e.g. [[r...], [g...], [b...]]).
//  - Text: one vector per line, numbers separated by whitespace; with C channels a line holds
//    the C channels one after another (all N^2 of channel 0, then channel 1, ...). Blank lines
//    and lines starting with '#' are skipped.
// Every vector has the same length; N^2 must be a square; every number must be finite.
// Numbers are read exactly as JSON (text layout: decimal or exponent form, an optional leading +).
#pragma once

#include <cstddef>
#include <string>
#include <vector>
#include "zhf/io/limits.h"
#include "zhf/runtime/limits.h"

namespace zhf::io {

struct CoefficientFile {
  int order = 0;
  int channels = 1;
  std::vector<std::vector<double>> signals;  // one per vector and channel, N^2 each
};

// Limits (io/limits.h): orders up to runtime::kMaxShOrder, files up to kMaxCoefficientBytes,
// channels up to kMaxChannels, magnitudes up to kMaxCoefficientMagnitude.
//
// channels: 0 to take it from the JSON nesting (text then means 1). Throws InputError naming
// the source and the vector (line for text) that is wrong.
CoefficientFile parse_coefficients(const std::string& text, const std::string& source, int channels = 0);
CoefficientFile read_coefficients(const std::string& path, int channels = 0);

}  // namespace zhf::io
