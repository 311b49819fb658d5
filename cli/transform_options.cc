#include "transform_options.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include "commands.h"
#include "zhf/io/errors.h"
#include "zhf/io/rotation_text.h"
#include "zhf/runtime/rotation.h"
#include "zhf/tolerances/tolerances.h"

namespace zhf::cli {
namespace {


// The one rotation form given: its option, its text and how to read it.
struct GivenForm {
  std::string option, text;
  io::RotationForm form;
};

GivenForm given_form(const TransformOptions& o) {
  std::vector<GivenForm> given;
  if (!o.matrix.empty())
    given.push_back({"--matrix", o.matrix, o.column_major ? io::RotationForm::kMatrixColumnMajor : io::RotationForm::kMatrix});
  if (!o.zyz.empty()) given.push_back({"--zyz", o.zyz, io::RotationForm::kZyz});
  if (!o.axis_angle.empty()) given.push_back({"--axis-angle", o.axis_angle, io::RotationForm::kAxisAngle});
  if (!o.quat.empty()) given.push_back({"--quat", o.quat, io::RotationForm::kQuaternionWxyz});
  if (!o.quat_xyzw.empty()) given.push_back({"--quat-xyzw", o.quat_xyzw, io::RotationForm::kQuaternionXyzw});
  if (!o.euler.empty()) given.push_back({"--euler", o.euler, io::RotationForm::kEuler});
  if (given.size() != 1) throw UsageError("give exactly one of --matrix, --zyz, --axis-angle, --quat, --quat-xyzw, --euler");
  if (o.column_major && o.matrix.empty()) throw UsageError("--column-major: applies to --matrix only");
  const bool euler = !o.euler.empty();
  if (euler != !o.euler_order.empty()) throw UsageError("--euler and --euler-order go together");
  if (euler && o.intrinsic == o.extrinsic) throw UsageError("--euler: say --intrinsic or --extrinsic");
  if (!euler && (o.intrinsic || o.extrinsic)) throw UsageError("--intrinsic and --extrinsic apply to --euler only");
  return given.front();
}

// The transform the options give, checked: a non-finite entry or a defect above the tolerance
// is refused (the defect repaired on request); reflections are transforms too. What is
// accepted is replaced by the nearest orthogonal matrix, so a result computed in double is an
// orthogonal transform's to double precision.
}  // namespace

std::array<double, 9> transform_matrix(const TransformOptions& o, bool quiet) {
  const GivenForm given = given_form(o);
  io::ParsedRotation parsed;
  try {
    parsed = io::parse_rotation(given.text, given.form, given.option, {o.euler_order, o.extrinsic});
  } catch (const io::InputError& e) {
    throw UsageError(e.what());  // an option's text: a bad command line
  }
  if (!quiet && std::abs(parsed.quaternion_length - 1) > zhf::tolerance::kRotationDefect)
    std::fprintf(stderr, "zhf: %s: normalised (its length was %.6g)\n", given.option.c_str(), parsed.quaternion_length);
  const std::array<double, 9>& r = parsed.matrix;
  const runtime::RotationCheck check = runtime::validate_rotation(r.data(), zhf::tolerance::kRotationDefect,
                                                                  runtime::Handedness::kEither);
  if (!check.ok && (!o.repair || !check.finite))
    throw UsageError(given.option + ": " + check.message + (check.finite ? "; --repair uses the nearest orthogonal matrix" : ""));
  std::array<double, 9> nearest{};
  if (!runtime::nearest_orthogonal(r.data(), nearest.data())) throw UsageError(given.option + ": singular; cannot repair");
  const double defect = std::max(check.orthonormality, std::abs(std::abs(check.determinant) - 1));
  if (!check.ok) {
    std::fprintf(stderr, "zhf: %s: repaired to the nearest orthogonal matrix (%s)\n", given.option.c_str(), check.message.c_str());
  } else if (!quiet && defect > zhf::tolerance::kDoubleRoundingDefect) {
    std::fprintf(stderr, "zhf: %s: off orthonormal by %s; used the nearest orthogonal matrix\n", given.option.c_str(),
                 runtime::format_number(defect, 2).c_str());
  }
  return nearest;
}


bool transform_given(const TransformOptions& o) {
  return !o.matrix.empty() || !o.zyz.empty() || !o.axis_angle.empty() || !o.quat.empty() || !o.quat_xyzw.empty() ||
         !o.euler.empty() || !o.euler_order.empty() || o.column_major || o.intrinsic || o.extrinsic || o.repair;
}

void add_transform_options(CLI::App* c, TransformOptions& o) {
  c->add_option("--matrix", o.matrix, "Rotation or reflection: 9 numbers, row-major (maps v to R v)");
  c->add_flag("--column-major", o.column_major, "--matrix lists its 9 numbers column by column");
  c->add_option("--zyz", o.zyz, "Euler angles a b g in radians: R = Rz(a) Ry(b) Rz(g)");
  c->add_option("--axis-angle", o.axis_angle, "x y z angle: a right-handed turn (radians) about the axis");
  c->add_option("--quat", o.quat, "Quaternion w x y z (scalar first; normalised, with a note if not unit)");
  c->add_option("--quat-xyzw", o.quat_xyzw, "Quaternion x y z w (scalar last)");
  c->add_option("--euler", o.euler, "Euler angles a b c in radians about the axes of --euler-order");
  c->add_option("--euler-order", o.euler_order, "Axes of --euler: three of X, Y, Z, e.g. XYZ, ZYX, ZXZ");
  c->add_flag("--intrinsic", o.intrinsic, "--euler turns about the axes as turned: R = R1(a) R2(b) R3(c)");
  c->add_flag("--extrinsic", o.extrinsic, "--euler turns about the fixed axes: R = R3(c) R2(b) R1(a)");
  c->add_flag("--repair", o.repair,
              "Accept a matrix off orthonormal by more than " + runtime::format_number(zhf::tolerance::kRotationDefect) +
                  " too; every matrix is replaced by the nearest orthogonal one");
}

}  // namespace zhf::cli
