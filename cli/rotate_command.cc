#include <cstdio>
#include <filesystem>
#include <memory>

#include "commands.h"
#include "zhf/io/coefficients.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/rotation_text.h"
#include "zhf/runtime/rotation_check.h"
#include "zhf/runtime/rotator.h"

namespace zhf::cli {
namespace {

struct RotateOptions {
  std::string coeffs;
  int channels = 0;
  std::string matrix, zyz, axis_angle;
  bool repair = false;
  std::string tables;
  std::string out;
};

int run_rotate(const RotateOptions& o) {
  const int forms = !o.matrix.empty() + !o.zyz.empty() + !o.axis_angle.empty();
  if (forms != 1) throw UsageError("give exactly one of --matrix, --zyz, --axis-angle");
  std::array<double, 9> r{};
  if (!o.matrix.empty()) r = io::parse_rotation(o.matrix, io::RotationForm::kMatrix, "--matrix");
  if (!o.zyz.empty()) r = io::parse_rotation(o.zyz, io::RotationForm::kZyz, "--zyz");
  if (!o.axis_angle.empty()) r = io::parse_rotation(o.axis_angle, io::RotationForm::kAxisAngle, "--axis-angle");
  const std::string option = !o.matrix.empty() ? "--matrix" : !o.zyz.empty() ? "--zyz" : "--axis-angle";
  const runtime::RotationCheck check = runtime::validate_rotation(r.data());
  if (!check.ok) {
    if (!o.repair || check.determinant < 0 || !check.finite)
      throw io::InputError(option + ": " + check.message + (check.determinant < 0 || !check.finite ? "" : "; --repair uses the nearest rotation"));
    std::array<double, 9> fixed{};
    if (!runtime::nearest_rotation(r.data(), fixed.data())) throw io::InputError(option + ": singular; cannot repair");
    std::fprintf(stderr, "zhf: %s: repaired to the nearest rotation (%s)\n", option.c_str(), check.message.c_str());
    r = fixed;
  }
  const io::CoefficientFile file = io::read_coefficients(o.coeffs, o.channels);
  const int order = file.order;
  // Order 1 is band 0 alone, which no rotation changes.
  const runtime::Rotator<double> rotator = [&] {
    if (order == 1) return runtime::Rotator<double>();
    if (order <= runtime::kMaxGeneratedOrder) return runtime::Rotator<double>::generated(order);
    const std::string table = (o.tables.empty() ? project_path("generated/lobes") : o.tables) + "/order_" + std::to_string(order) + ".json";
    if (!std::filesystem::exists(table))
      throw io::InputError(o.coeffs + ": order " + std::to_string(order) + " has no lobe table (" + table + ")");
    return runtime::Rotator<double>::from_table(runtime::read_lobe_table(table));
  }();
  nlohmann::ordered_json vectors = nlohmann::ordered_json::array();
  const size_t n = static_cast<size_t>(order) * order;
  std::vector<double> out(n);
  for (size_t s = 0; s < file.signals.size(); s += file.channels) {
    nlohmann::ordered_json channels = nlohmann::ordered_json::array();
    for (int c = 0; c < file.channels; ++c) {
      if (order == 1) {
        out = file.signals[s + c];
      } else {
        rotator.rotate(r.data(), file.signals[s + c].data(), out.data());
      }
      channels.push_back(out);
    }
    vectors.push_back(file.channels == 1 ? channels[0] : channels);
  }
  io::write_file_atomically(o.out, io::json_text(vectors));
  std::printf("rotated %zu vectors (order %d, %d channel%s) into %s\n", file.signals.size() / file.channels, order,
              file.channels, file.channels == 1 ? "" : "s", o.out.c_str());
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
  c->add_flag("--repair", o->repair, "Replace a matrix that is off orthonormal by the nearest rotation instead of rejecting it");
  c->add_option("--tables", o->tables, "Lobe tables for orders above 8 (default generated/lobes)");
  c->add_option("--out", o->out, "Write the rotated vectors here (JSON)")->required();
  c->callback([o, &action] { action = [o] { return run_rotate(*o); }; });
}

}  // namespace zhf::cli
