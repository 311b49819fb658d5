// The functions zhf emits for one order, built once on the expression graph and printed by
// every backend.
//
// Rotation by lobes (bands >= 2): with lobe d's unit direction w_d = u_d / |u_d|, where u_d is
// w_d rescaled so its components are +-1 where they can be (then R u_d is additions only),
// and with band-l SH homogeneous of degree l (r^2 = |u_d|^2 is a compile-time constant),
//   f'_{l,m} = K_{l,m} sum_d H_{l,m}(R u_d) zhat_{l,d},
//   zhat_{l,d} = sum_m' (A_l[m'][d] / |u_d|^l) f_{l,m'}   (sparse: A^T with scale folded in)
// where H are the scaled Legendre-times-(x+iy)^m polynomials of runtime/sh_eval.h and K_{l,m} collects
// every normalisation: one multiply per output instead of one per lobe.
//
// Rotation by zxzxz (a band's other form): with zyz Euler angles R = Rz(a) Ry(b) Rz(g) and
// Ry(b) = Rx(-90) Rz(b) Rx(+90),
//   f'_l = Z_l(a) X_l^T Z_l(b) X_l Z_l(g) f_l,   X_l = D_l(Rx(+90 deg)) (constants, zeros folded),
// where Z_l(t) turns each (cos m phi, sin m phi) pair by m t: 4l multiplies. The angles are never
// formed: cos and sin of a come from R's last column normalised (one reciprocal square root; a
// fixed choice at gimbal lock, where any a works), those of g from Rz(-a) R's middle row, b's are
// R_22 and |R's last column in xy|, and the multiples m t by doubling and angle addition.
#pragma once

#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "zhf/codegen/expr.h"
#include "zhf/runtime/lobe_stage.h"
#include "zhf/runtime/lobe_table.h"

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

// What an emitted function computes; the manifest records it, so nothing downstream (verify,
// the benchmarks, the runtime's dispatch) ever recovers it from a name.
enum class KernelKind {
  kShEval,              // sh_eval_orderN(dir, y): every band at a unit direction
  kLobeWeights,         // lobe_weights_orderN(f, z): z = A^T f per band >= 2
  kFromSamples,         // coefficients_from_samples_orderN(s, f): f = A s per band >= 2
  kRotate,              // rotate[_rgb|_rgba]_orderN(R, coeffs, rotated)
  kSignalTailored,      // rotate_signal_tailored[_rgb|_rgba]_orderN(R, coeffs, rotated)
  kBatch,               // rotate_batch_orderN(count, R, coeffs, rotated), structure of arrays (C++)
  kRotationMatrices,    // rotation_matrices_orderN(R, M): the dense band matrices
  kApplyMatrices,       // apply_rotation_matrices[_rgb|_rgba]_orderN(M, coeffs, rotated)
  kZonal,               // rotate_zonal[_rgb|_rgba]_orderN(R, axis, zonal, rotated)
  kProduct,             // product_orderN(f, g, h): h = P_N(f g), the SH product (runtime/product.h)
  kSquare,              // square_orderN(f, h): h = P_N(f^2)
  kShade,               // shade_orderN(R, light, transfer, result): int light(R^T w) transfer(w) dw
  kShadeLobes,          // shade_lobes_orderN(R, z, transfer, result): the same from light's lobe weights
};
const char* kernel_kind_name(KernelKind kind);
bool parse_kernel_kind(const std::string& name, KernelKind& kind);

struct Function {
  std::string name;
  std::string member;      // the name without "_orderN": its name in the Kernels<N> trait
  KernelKind kind = KernelKind::kRotate;
  int channels = 1;
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

// What a module is printed as: the rotation kernels of a sparse table, or the constant tables
// of the lobe-parallel kernel (runtime/lanes.h) from a lanes table.
enum class ModuleKind { kKernels, kLanesTables };

// How a rotation kernel rotates one band l >= 2 (bands 0 and 1 are a copy and a 3x3): by its
// lobes, by zxzxz, or (band 2 only) as the symmetric traceless matrix M of its quadratic form,
// M' = R M R^T.
enum class BandMethod { kLobes, kZxzxz, kQuadratic };
const char* band_method_name(BandMethod method);  // "zhf", "zxzxz", "quadratic"

struct Module {
  ModuleKind kind = ModuleKind::kKernels;
  int order = 0;
  runtime::LobeTable table;
  std::vector<Lobe> lobes;
  std::vector<Function> functions;
  runtime::LobeStage lobe_stage = runtime::LobeStage::kFloat;  // of the rotations (kernels), or of lanes.h
  std::vector<BandMethod> band_methods;  // [l] of the rotation kernels (rotate, rotate_batch); bands 0, 1 unused
  std::string band_methods_reason;       // why, for the banner

  // Where the rotation kernels run their lobe stage: lobe_stage, or float when no band is by lobes.
  runtime::LobeStage rotation_lobe_stage() const;
};

// Which functions a module holds. The defaults are generated/'s; a scene spec narrows them.
// Channel counts are 1, 3 (suffix _rgb) or 4 (_rgba); multi-channel functions share the
// per-rotation work across channels.
struct ModuleOptions {
  bool sh_eval = true;
  bool lobe_multiplies = true;                   // lobe_weights / coefficients_from_samples (orders >= 3)
  std::vector<int> standard_channels = {1, 3};   // rotate[_rgb|_rgba]
  std::vector<int> tailored_channels = {1};      // rotate_signal_tailored[_rgb|_rgba]
  bool batch = true;                             // rotate_batch, emitted by backends that support it
  std::vector<int> dense_channels;               // rotation_matrices + apply_rotation_matrices[_rgb|_rgba]
  std::vector<int> zonal_channels;               // rotate_zonal[_rgb|_rgba]
  std::vector<int> zero_bands;                   // known zero: their outputs are 0 and cost nothing
  bool products = true;                          // product and square (no table needed)
  bool shading = true;                           // shade (and shade_lobes with lobe_multiplies)
  // Every function in the Condon-Shortley sign convention (runtime/conventions.h: 3dgs,
  // condon-shortley): coefficients carry (-1)^m, R and directions are in the system's axes. The
  // system's coefficients are zhf's of f(K u) (K = diag(-1, -1, 1)), so rotations compute zhf's
  // with K R K, sh_eval and zonal axes take K d, and the lobe functions, whose lobes stay at the
  // table's coordinates in the system's axes, take or give S f (S = (-1)^m). All folded into the
  // graph: the same multiplies, a few negations at most.
  bool condon_shortley = false;
  // Where float rotations run their lobe stage (runtime/lobe_stage.h); none: automatic, the
  // cheapest stage whose float error model meets tolerance::kFloatRotation.
  std::optional<runtime::LobeStage> lobe_stage;
  // How the rotation kernels rotate each band >= 2: every band by one method (quadratic: band 2
  // so, the others by zxzxz), or none: automatic, the assignment of methods to bands (band 2 may
  // also be quadratic) with the fewest operations in rotate_orderN.
  std::optional<BandMethod> band_method;
};

// The names a method choice takes: "auto" (none), then each method's.
std::vector<std::string> band_method_choices();
// "auto" (none) or a method's name; false otherwise.
bool parse_band_method_choice(const std::string& name, std::optional<BandMethod>& method);
std::string band_method_choice_name(const std::optional<BandMethod>& method);

// The lobe stage `auto` picks for a table's rotation kernels: float where eps_f (N-1) k_max meets
// the float target, else double (R projected, the whole lobe stage in double).
runtime::LobeStage automatic_lobe_stage(const runtime::LobeTable& table);
// The names a lobe-stage choice takes: "auto" (none), then each stage's.
std::vector<std::string> lobe_stage_choices();
// "auto" (none: automatic_lobe_stage) or a stage's name (runtime/lobe_stage.h); false otherwise.
bool parse_lobe_stage_choice(const std::string& name, std::optional<runtime::LobeStage>& stage);
std::string lobe_stage_choice_name(const std::optional<runtime::LobeStage>& stage);
// The one a module of this table gets with these options.
runtime::LobeStage lobe_stage_for(const runtime::LobeTable& table, const ModuleOptions& options);

// "", "_rgb" or "_rgba".
std::string channel_suffix(int channels);
// Packed dense band matrices for bands 0..order-1: band l's (2l+1)^2 block, row-major, starts at
// l(2l-1)(2l+1)/3.
int dense_matrix_offset(int band);

// The SH product kernels (product_kernels.cc): the Gaunt sum with shared pair products, or
// Gauss-Legendre nodes in z with the phi products done by trigonometric identities.
// condon_shortley: coefficients in and out carry (-1)^m (S h = P(S f, S g): products commute with
// the change of axes), folded into the graph.
enum class ProductFactoring { kPairs, kGaussFourier };
const char* product_factoring_name(ProductFactoring factoring);
Function product_function(int order, bool square, ProductFactoring factoring, bool condon_shortley = false);
// The one of the two with fewer multiplies.
Function product_function(int order, bool square, bool condon_shortley = false);
// The flat indices of odd m below count: where S = (-1)^m negates.
std::vector<int> odd_m_indices(int count);

// The multiplies of one band's lobe weights z = A^T f as emitted by lobe_weights (equal
// magnitudes in a column share a multiply, shared sums are made once), for A = inverse.
int lobe_weight_multiplies(const runtime::Matrix& inverse);

// The multiplies of rotate_orderN with every band by lobes (--method zhf), one channel.
int lobe_rotation_multiplies(const runtime::LobeTable& table);
// The part of lobe_rotation_multiplies that depends on the lobe set, built as the kernel builds
// it: each band's lobe weights with the lobes' scales folded in, R's projection onto the
// rotations where the table's condition puts the lobe stage in double, R u_d (products shared
// where the lobes' coordinates repeat) and, without lobe sharing, the SH at R u_d (a direction
// that serves several bands is evaluated once). The rest (band 1, with sharing the SH at the
// rotated lobes, the sums over the lobes, the output scales) is the same for every table of one
// order and lobe sharing (tests/codegen/codegen_test.cc), so ranking lobe sets by this ranks them
// by the whole kernel: what `zhf optimize --objective operations` minimises. With sharing it
// builds a graph of the lobe weights' size, a fraction of the kernel's.
int lobe_dependent_multiplies(const runtime::LobeTable& table);

// Order 2 needs no table: pass runtime::lobe_free_table().
Module build_module(const runtime::LobeTable& table, const ModuleOptions& options);

// The lanes tables' module: the table, and the cheapest lobe stage whose float error model
// eps_f (N-1) a_max times its margin (runtime/tolerances.h) meets the float target.
Module build_lanes_module(const runtime::LobeTable& table);
double lanes_float_error_model(const runtime::LobeTable& table);

}  // namespace zhf::codegen
