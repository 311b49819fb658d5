#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
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
#include "zhf/runtime/conventions.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/rotation.h"
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
  // Every order through zhf::dispatch: its fastest kernels, or with --tables the rotation of the
  // order's lobe table from that folder (runtime::Rotator::from_table; order 1, band 0 alone, has
  // no lobes to take).
  std::optional<runtime::LobeTable> table;
  if (!o.tables.empty() && order > 1) {
    const std::string path = runtime::table_path(o.tables, order);
    if (order > runtime::kMaxTableOrder || !std::filesystem::exists(path))
      throw io::InputError("--tables: order " + std::to_string(order) + " has no lobe table (" + path + ")");
    table = runtime::read_lobe_table(path, order);
  }
  const auto rotator = dispatch::Rotator<double>::make(order, table ? &*table : nullptr);
  const size_t n = static_cast<size_t>(order) * order, count = file.signals.size();
  std::vector<double> in(count * n), out(count * n);
  for (size_t v = 0; v < count; ++v) std::copy(file.signals[v].begin(), file.signals[v].end(), in.begin() + n * v);
  rotator.transform_shared(count, r.data(), in.data(), out.data(), 1);
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
  std::printf("rotated %s (order %d, %d channel%s; %s path, %s kernels) into %s\n", counted(file.signals.size() / file.channels, "vector").c_str(),
              order, file.channels, file.channels == 1 ? "" : "s", dispatch::isa_name(rotator.isa()), rotator.path().c_str(), o.out.c_str());
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
  c->add_option("--tables", o->tables, "Rotate with the lobe table order_N.json in this folder (its lobes where they are the faster path, else zxzxz; the kernels printed say which)");
  c->add_option("--out", o->out, "Write the rotated vectors here (JSON)")->required();
  c->callback([o, &action] { action = [o] { return run_rotate(*o); }; });
}

}  // namespace zhf::cli
