#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "commands.h"
#include "options.h"
#include "transform_options.h"
#include "zhf/dispatch/rotator.h"
#include "zhf/io/coefficients.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/limits.h"
#include "zhf/io/signals.h"
#include "zhf/pipeline/data_root.h"
#include "zhf/runtime/conventions.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/orthogonal.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/rotator.h"
#include "zhf/runtime/table_io.h"

namespace zhf::cli {
namespace {

struct RotateOptions {
  std::string coeffs;
  int channels = 0;
  TransformOptions transform;
  std::string convention = "zhf";
  std::string tables;
  std::string out;
};

int run_rotate(const RotateOptions& o) {
  const runtime::Convention* convention = runtime::find_convention(o.convention);
  if (!convention)
    throw UsageError("--convention: '" + runtime::excerpt(o.convention) + "' is not one of " + runtime::convention_names());
  const std::array<double, 9> r = convention->rotation_in_zhf_terms(transform_matrix(o.transform));
  io::PendingFile out_file(o.out);  // refuse an unwritable output before the work
  const io::CoefficientFile file = io::read_coefficients(o.coeffs, o.channels);
  const int order = file.order;
  // Order 1 is band 0 alone, which no rotation changes. The generated orders run on the CPU's
  // fastest path (zhf::dispatch); the orders above them through their lobe tables.
  std::optional<dispatch::Rotator<double>> fastest;
  std::unique_ptr<runtime::Rotator<double>> rotator;
  if (order > 1 && order <= runtime::kMaxGeneratedOrder) {
    fastest.emplace(dispatch::Rotator<double>::make(order));
  } else if (order > runtime::kMaxGeneratedOrder) {
    const std::string tables = o.tables.empty() ? pipeline::data_root().lobes() : o.tables;
    const std::string table = runtime::table_path(tables, order);
    if (order > runtime::kMaxTableOrder || !std::filesystem::exists(table))
      throw io::InputError(o.coeffs + ": order " + std::to_string(order) + " has no lobe table (" + table + ")");
    rotator = std::make_unique<runtime::Rotator<double>>(runtime::Rotator<double>::from_table(runtime::read_lobe_table(table, order)));
  }
  const size_t n = static_cast<size_t>(order) * order, count = file.signals.size();
  std::vector<double> in(count * n), out(count * n);
  for (size_t v = 0; v < count; ++v) std::copy(file.signals[v].begin(), file.signals[v].end(), in.begin() + n * v);
  if (fastest) {
    fastest->transform_shared(count, r.data(), in.data(), out.data(), 1);
  } else if (rotator) {
    const runtime::OrthogonalTransform<double> transform(*rotator, r.data());
    for (size_t v = 0; v < count; ++v) transform.apply(in.data() + n * v, out.data() + n * v);
  } else {
    out = in;
  }
  nlohmann::ordered_json vectors = nlohmann::ordered_json::array();
  for (size_t s = 0; s < count; s += file.channels) {
    nlohmann::ordered_json channels = nlohmann::ordered_json::array();
    for (int c = 0; c < file.channels; ++c)
      channels.push_back(std::vector<double>(out.begin() + n * (s + c), out.begin() + n * (s + c + 1)));
    vectors.push_back(file.channels == 1 ? channels[0] : channels);
  }
  out_file.write(io::json_text(vectors));
  io::throw_if_interrupted();
  out_file.commit();
  std::printf("rotated %s (order %d, %d channel%s) into %s\n", counted(file.signals.size() / file.channels, "vector").c_str(), order, file.channels,
              file.channels == 1 ? "" : "s", o.out.c_str());
  return kExitOk;
}

}  // namespace

void add_rotate_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<RotateOptions>();
  CLI::App* c = app.add_subcommand("rotate", "Rotate SH coefficient vectors from a file (double precision)");
  c->add_option("--coeffs", o->coeffs, "Coefficient vectors (JSON array or text; as zhf analyze reads them)")->required();
  c->add_option("--channels", o->channels, "Channels per vector")->check(CLI::Range(1, io::kMaxChannels));
  add_transform_options(c, o->transform);
  c->add_option("--convention", o->convention,
                "The coefficients' convention, the rotation in the same system's axes: " + runtime::convention_names() +
                    " (docs/conventions.md)");
  c->add_option("--tables", o->tables, "Lobe tables for orders above 8 (default generated/lobes)");
  c->add_option("--out", o->out, "Write the rotated vectors here (JSON)")->required();
  c->callback([o, &action] { action = [o] { return run_rotate(*o); }; });
}

}  // namespace zhf::cli
