// What verify runs every kernel on, and what each kernel must give: one input set per order for
// all languages (the fixed extreme rotations, then random ones, each with a random unit-norm
// coefficient vector and a zonal axis), and the double reference outputs of sh/.
#pragma once

#include <string>
#include <vector>

#include "zhf/codegen/kernels.h"
#include "zhf/io/limits.h"
#include "zhf/runtime/lobe_table.h"

namespace zhf::verify {

// Every output holds up to kMaxChannels channels: output v of a mode is at [v * kMaxChannels * n].
using io::kMaxChannels;
// Per input in the rotations stream: R (9) and the zonal axis (3).
constexpr int kRotationStride = 12;

struct Inputs {
  int order = 0;
  int count = 0;
  std::vector<double> rotations;   // 9 per input, row-major
  std::vector<double> axes;        // 3 per input: the zonal functions' axes
  std::vector<double> coeffs;      // N^2 per input, unit norm, zero on known-zero bands
  std::vector<std::string> names;  // the extreme inputs' names ("random" for the rest)
  std::vector<bool> live;          // per band: not known to be zero

  // R and the axis of every input, kRotationStride each.
  std::vector<double> rotation_stream() const;
};

// One function checked: its kind and channel count (an apply-matrices mode also runs
// rotation_matrices; a lanes mode runs runtime/lanes.h's rotate_lanes of the order).
struct Mode {
  codegen::KernelKind kind = codegen::KernelKind::kRotate;
  int channels = 1;
  std::string function;
  bool lanes = false;
};

// Channel c of input v is rotation v applied to the coefficients of input (v + c) % count;
// the zonal weights of channel c are the first N coefficients of that input.
Inputs make_inputs(int order, int random_count, const runtime::LobeTable& table, const std::vector<int>& zero_bands);

// reference[mode][v * kMaxChannels * n + c * n + k], from the Ivanic-Ruedenberg rotation.
std::vector<std::vector<double>> reference_outputs(const Inputs& in, const runtime::LobeTable& table,
                                                   const std::vector<Mode>& modes);

// Floats in the packed dense band matrices of an order (codegen::dense_matrix_offset(order)).
int dense_size(int order);

}  // namespace zhf::verify
