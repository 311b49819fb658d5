// The functions zhf emits for one order, built once on the expression graph and printed by
// every backend.
//
// Rotation by lobes (bands >= 2): with lobe d's unit direction w_d = u_d / |u_d|, where u_d is
// w_d rescaled so its components are +-1 where they can be (then R u_d is additions only),
// and with band-l SH homogeneous of degree l (r^2 = |u_d|^2 is a compile-time constant),
//   f'_{l,m} = K_{l,m} sum_d H_{l,m}(R u_d) zhat_{l,d},
//   zhat_{l,d} = sum_m' (A_l[m'][d] / |u_d|^l) f_{l,m'}   (sparse: A^T with scale folded in)
// where H are the scaled Legendre-times-(x+iy)^m polynomials of eval.h and K_{l,m} collects
// every normalisation: one multiply per output instead of one per lobe.
#pragma once

#include <string>
#include <tuple>
#include <vector>

#include "zhf/codegen/expr.h"
#include "zhf/codegen/float_model.h"
#include "zhf/optimizer/lobe_table.h"

namespace zhf::codegen {

struct Param {
  std::string name;
  int size = 0;            // elements per channel
  bool output = false;
  int channels = 1;        // 3 or 4: planar [channels][size] in C++, float3/float4[size] in shaders
};

struct Output {
  int param = 0;
  int element = 0;
  int node = 0;
};

struct Function {
  std::string name;
  std::string doc;         // one line: what it computes
  std::vector<Param> params;
  Graph graph;
  std::vector<Output> outputs;
  bool batch = false;      // C++ only: loop over count vectors in structure-of-arrays layout

  std::vector<int> output_nodes() const;
};

struct Lobe {
  double unit[3];          // w_d
  double scaled[3];        // u_d
  std::string source;
};

struct Module {
  int order = 0;
  optimizer::LobeTable table;
  std::vector<Lobe> lobes;
  std::vector<Function> functions;
  bool wide_lobes = false;  // the rotations' lobe stage runs in double
};

// Where the lobe stage of the rotations runs: in double for float kernels whose table's error
// model misses kFloatRotationTarget (auto), always, or in the kernel's own type (float: fastest,
// error up to the model).
enum class LobePrecision { kAuto, kFloat, kDouble };

// Which functions a module holds. The defaults are generated/'s; a scene spec narrows them.
// Channel counts are 1, 3 (suffix _rgb) or 4 (_rgba); multi-channel functions share the
// per-rotation work across channels.
struct ModuleOptions {
  bool sh_eval = true;
  bool lobe_multiplies = true;                   // AhatTransposeMultiply / AhatMultiply (orders >= 3)
  std::vector<int> standard_channels = {1, 3};   // rotate[_rgb|_rgba]
  std::vector<int> tailored_channels = {1};      // rotate_signal_tailored[_rgb|_rgba]
  bool batch = true;                             // rotate_batch, emitted by backends that support it
  std::vector<int> dense_channels;               // rotation_matrices + apply_rotation_matrices[_rgb|_rgba]
  std::vector<int> zonal_channels;               // rotate_zonal[_rgb|_rgba]
  std::vector<int> zero_bands;                   // known zero: their outputs are 0 and cost nothing
  LobePrecision lobe_precision = LobePrecision::kAuto;
};

// Whether float kernels must run the lobe stage (R's projection onto the rotations, the
// rotated lobes, their SH, the sums over lobes) in double to stay within the target.
bool float_needs_wide_lobes(const optimizer::LobeTable& table);
// The lobe precision resolved for a table: true for double.
bool wide_lobes(const optimizer::LobeTable& table, LobePrecision precision);
// "auto", "float", "double"; parse returns false on anything else.
std::string lobe_precision_name(LobePrecision precision);
bool parse_lobe_precision(const std::string& text, LobePrecision& precision);

// "", "_rgb" or "_rgba".
std::string channel_suffix(int channels);
// Packed dense band matrices for bands 0..order-1: band l's (2l+1)^2 block, row-major, starts at
// l(2l-1)(2l+1)/3.
int dense_matrix_offset(int band);

// Order 2 needs no table: pass a table with order 2 and no lobes.
Module build_module(const optimizer::LobeTable& table, const ModuleOptions& options);

// The lobe-free order-2 table.
optimizer::LobeTable order2_table();

}  // namespace zhf::codegen
