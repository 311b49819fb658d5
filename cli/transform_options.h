// The orthogonal transform a user types, shared by zhf rotate and zhf splat: one of --matrix
// (row-major, or --column-major), --zyz, --axis-angle, --quat, --quat-xyzw, --euler with
// --euler-order and --intrinsic or --extrinsic; reflections included. Checked, repaired on
// request (--repair), and replaced by the nearest orthogonal matrix.
#pragma once

#include <array>
#include <string>

#include <CLI/CLI.hpp>

namespace zhf::cli {

struct TransformOptions {
  std::string matrix, zyz, axis_angle, quat, quat_xyzw, euler, euler_order;
  bool column_major = false, intrinsic = false, extrinsic = false;
  bool repair = false;
};

void add_transform_options(CLI::App* command, TransformOptions& o);

// Throws UsageError naming the option. Notes on stderr (a quaternion normalised, the nearest
// rotation used) unless quiet.
std::array<double, 9> transform_matrix(const TransformOptions& o, bool quiet = false);
// Whether any of the options above was given (a rotation, or a word about one).
bool transform_given(const TransformOptions& o);

}  // namespace zhf::cli
