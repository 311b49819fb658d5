#include <cstdio>
#include <filesystem>
#include <memory>

#include "commands.h"
#include "zhf/io/coefficients.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/rotation_text.h"
#include "zhf/io/signals.h"
#include "zhf/pipeline/project.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/rotator.h"
#include "zhf_kernels.h"

namespace zhf::cli {
namespace {

// A rotation off orthonormal by more than a few double roundings: worth saying that the nearest
// rotation was used instead.
constexpr double kDoubleRoundingDefect = 1e-14;

struct RotateOptions {
  std::string coeffs;
  int channels = 0;
  std::string matrix, zyz, axis_angle;
  bool repair = false;
  std::string tables;
  std::string out;
};

// The rotation the options give, checked: a reflection, a non-finite entry or a defect above the
// tolerance is refused (the defect repaired on request); what is accepted is replaced by the
// nearest rotation, so a result computed in double is a rotation's to double precision.
std::array<double, 9> rotation(const RotateOptions& o) {
  const int forms = !o.matrix.empty() + !o.zyz.empty() + !o.axis_angle.empty();
  if (forms != 1) throw UsageError("give exactly one of --matrix, --zyz, --axis-angle");
  const std::string option = !o.matrix.empty() ? "--matrix" : !o.zyz.empty() ? "--zyz" : "--axis-angle";
  const io::RotationForm form = !o.matrix.empty() ? io::RotationForm::kMatrix
                                : !o.zyz.empty()  ? io::RotationForm::kZyz
                                                  : io::RotationForm::kAxisAngle;
  std::array<double, 9> r{};
  try {
    r = io::parse_rotation(!o.matrix.empty() ? o.matrix : !o.zyz.empty() ? o.zyz : o.axis_angle, form, option);
  } catch (const io::InputError& e) {
    throw UsageError(e.what());  // an option's text: a bad command line
  }
  const runtime::RotationCheck check = runtime::validate_rotation(r.data());
  const bool repairable = check.finite && check.determinant > 0;
  if (!check.ok && (!o.repair || !repairable))
    throw UsageError(option + ": " + check.message + (repairable ? "; --repair uses the nearest rotation" : ""));
  std::array<double, 9> nearest{};
  if (!runtime::nearest_rotation(r.data(), nearest.data())) throw UsageError(option + ": singular; cannot repair");
  const double defect = std::max(check.orthonormality, std::abs(check.determinant - 1));
  if (!check.ok) {
    std::fprintf(stderr, "zhf: %s: repaired to the nearest rotation (%s)\n", option.c_str(), check.message.c_str());
  } else if (defect > kDoubleRoundingDefect) {
    std::fprintf(stderr, "zhf: %s: off orthonormal by %.2g; rotated by the nearest rotation\n", option.c_str(), defect);
  }
  return nearest;
}

int run_rotate(const RotateOptions& o) {
  const std::array<double, 9> r = rotation(o);
  io::PendingFile out_file(o.out);  // refuse an unwritable output before the work
  const io::CoefficientFile file = io::read_coefficients(o.coeffs, o.channels);
  const int order = file.order;
  // Order 1 is band 0 alone, which no rotation changes.
  std::unique_ptr<runtime::Rotator<double>> rotator;
  if (order > 1 && order <= runtime::kMaxGeneratedOrder) {
    rotator = std::make_unique<runtime::Rotator<double>>(runtime::Rotator<double>::with(gen::fastest_kernels<double>(order)));
  } else if (order > runtime::kMaxGeneratedOrder) {
    const std::string tables = o.tables.empty() ? pipeline::project().lobes() : o.tables;
    const std::string table = tables + "/order_" + std::to_string(order) + ".json";
    if (order > runtime::kMaxTableOrder || !std::filesystem::exists(table))
      throw io::InputError(o.coeffs + ": order " + std::to_string(order) + " has no lobe table (" + table + ")");
    rotator = std::make_unique<runtime::Rotator<double>>(runtime::Rotator<double>::from_table(runtime::read_lobe_table(table, order)));
  }
  nlohmann::ordered_json vectors = nlohmann::ordered_json::array();
  const size_t n = static_cast<size_t>(order) * order;
  std::vector<double> out(n);
  for (size_t s = 0; s < file.signals.size(); s += file.channels) {
    nlohmann::ordered_json channels = nlohmann::ordered_json::array();
    for (int c = 0; c < file.channels; ++c) {
      if (rotator) {
        rotator->rotate(r.data(), file.signals[s + c].data(), out.data());
      } else {
        out = file.signals[s + c];
      }
      channels.push_back(out);
    }
    vectors.push_back(file.channels == 1 ? channels[0] : channels);
  }
  out_file.write(io::json_text(vectors));
  io::throw_if_interrupted();
  out_file.commit();
  std::printf("rotated %zu vectors (order %d, %d channel%s) into %s\n", file.signals.size() / file.channels, order, file.channels,
              file.channels == 1 ? "" : "s", o.out.c_str());
  return kExitOk;
}

}  // namespace

void add_rotate_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<RotateOptions>();
  CLI::App* c = app.add_subcommand("rotate", "Rotate SH coefficient vectors from a file (double precision)");
  c->add_option("--coeffs", o->coeffs, "Coefficient vectors (JSON array or text; as zhf analyze reads them)")->required();
  c->add_option("--channels", o->channels, "Channels per vector")->check(CLI::Range(1, 4));
  c->add_option("--matrix", o->matrix, "Row-major rotation: 9 numbers (maps v to R v)");
  c->add_option("--zyz", o->zyz, "Euler angles a b g in radians: R = Rz(a) Ry(b) Rz(g)");
  c->add_option("--axis-angle", o->axis_angle, "x y z angle: a right-handed turn (radians) about the axis");
  c->add_flag("--repair", o->repair,
              "Accept a matrix off orthonormal by more than 1e-5 too (reflections never); every matrix is replaced by the "
              "nearest rotation");
  c->add_option("--tables", o->tables, "Lobe tables for orders above 8 (default generated/lobes)");
  c->add_option("--out", o->out, "Write the rotated vectors here (JSON)")->required();
  c->callback([o, &action] { action = [o] { return run_rotate(*o); }; });
}

}  // namespace zhf::cli
