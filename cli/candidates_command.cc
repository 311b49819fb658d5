#include <cstdio>
#include <iostream>
#include <memory>

#include "commands.h"
#include "zhf/candidates/candidates.h"
#include "zhf/io/files.h"

namespace zhf::cli {
namespace {

struct CandidatesOptions {
  int order = 0;
  std::string json_path;
};

int run_candidates(const CandidatesOptions& options) {
  const candidates::CandidateSet set = candidates::enumerate_candidates(options.order);
  std::printf("order %d: %zu theta values, %zu phi values, %zu candidate directions\n", set.order,
              set.thetas.size(), set.phis.size(), set.directions.size());
  if (!options.json_path.empty()) {
    io::write_file_atomically(options.json_path, io::json_text(candidates::to_json(set)));
    std::printf("wrote %s\n", options.json_path.c_str());
  }
  return kExitOk;
}

}  // namespace

void add_candidates_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<CandidatesOptions>();
  CLI::App* command = app.add_subcommand("candidates", "Enumerate the candidate lobe directions of an order");
  command->add_option("--order", options->order, "Order N (bands 0..N-1)")
      ->required()
      ->check(CLI::Range(candidates::kMinOrder, candidates::kMaxOrder));
  command->add_option("--json", options->json_path, "Write the candidates as JSON to this file");
  command->callback([options, &action] { action = [options] { return run_candidates(*options); }; });
}

}  // namespace zhf::cli
