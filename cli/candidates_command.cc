#include <cstdio>
#include <memory>

#include "commands.h"
#include "options.h"
#include "zhf/candidates/candidates.h"
#include "zhf/candidates/limits.h"
#include "zhf/io/files.h"
#include "zhf/io/signals.h"

namespace zhf::cli {
namespace {


struct CandidatesOptions {
  std::string order;
  std::string json_path;
};

int run_candidates(const CandidatesOptions& options) {
  const int order =
      static_cast<int>(integer_option("--order", options.order, candidates::kMinSearchOrder, candidates::kMaxSearchOrder));
  if (!options.json_path.empty() && order > candidates::kMaxCandidatesJsonOrder)
    throw UsageError("--out: a candidates file goes up to order " + std::to_string(candidates::kMaxCandidatesJsonOrder) + " (order " +
                     std::to_string(order) + "'s would be too large to write)");
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
  command->add_option("--order", options->order, "Order N (bands 0..N-1), " + std::to_string(candidates::kMinSearchOrder) + ".." +
                                                      std::to_string(candidates::kMaxSearchOrder))->required();
  keep_old_spelling(command,
                    command->add_option("--out", options->json_path, "Write the candidates as JSON to this file (orders up to " +
                                                                       std::to_string(candidates::kMaxCandidatesJsonOrder) + ")"),
                    "--json", options->json_path);
  command->callback([options, &action] { action = [options] { return run_candidates(*options); }; });
}

}  // namespace zhf::cli
