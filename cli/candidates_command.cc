#include <cstdio>
#include <memory>

#include "commands.h"
#include "options.h"
#include "zhf/candidates/candidates.h"
#include "zhf/io/files.h"
#include "zhf/io/signals.h"
#include "zhf/runtime/limits.h"

namespace zhf::cli {
namespace {

struct CandidatesOptions {
  std::string order;
  std::string json_path;
};

int run_candidates(const CandidatesOptions& options) {
  const int order =
      static_cast<int>(integer_option("--order", options.order, runtime::kMinSearchOrder, runtime::kMaxSearchOrder));
  const candidates::CandidateSet set = candidates::enumerate_candidates(order);
  std::printf("order %d: %zu theta values, %zu phi values, %zu candidate directions\n", set.order, set.thetas.size(),
              set.phis.size(), set.directions.size());
  if (!options.json_path.empty()) {
    const std::string text = io::json_text(candidates::to_json(set));
    io::throw_if_interrupted();
    io::write_file_atomically(options.json_path, text);
    std::printf("wrote %s\n", options.json_path.c_str());
  }
  return kExitOk;
}

}  // namespace

void add_candidates_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<CandidatesOptions>();
  CLI::App* command = app.add_subcommand("candidates", "Enumerate the candidate lobe directions of an order");
  command->add_option("--order", options->order, "Order N (bands 0..N-1), 3..32")->required();
  command->add_option("--json", options->json_path, "Write the candidates as JSON to this file");
  command->callback([options, &action] { action = [options] { return run_candidates(*options); }; });
}

}  // namespace zhf::cli
