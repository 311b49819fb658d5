// zhf: sparse zonal-harmonic factorisation of SH rotation. Thin front end over the libraries.
#include <iostream>
#include <string>

#include "commands.h"
#include "zhf/io/errors.h"

namespace {

// "zhf" and the arguments, without the ones that cannot change an output (--threads,
// --quiet), so a recorded command reproduces the same bytes on any machine.
std::string recorded_command(int argc, char** argv) {
  std::string command = "zhf";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quiet") continue;
    if (arg == "--threads") {
      ++i;
      continue;
    }
    if (arg.rfind("--threads=", 0) == 0) continue;
    command += " " + arg;
  }
  return command;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace zhf::cli;
  CLI::App app{"zhf " ZHF_VERSION ": fast real spherical-harmonic rotation by sparse zonal-harmonic factorisation"};
  app.set_version_flag("--version", "zhf " ZHF_VERSION);
  app.require_subcommand(1);
  Action action;
  add_candidates_command(app, action);
  const std::string command = recorded_command(argc, argv);
  add_optimize_command(app, action, command);
  add_codegen_commands(app, action, command);
  add_verify_command(app, action);
  add_analyze_command(app, action);
  add_bench_command(app, action);
  add_rotate_command(app, action);
  if (argc > 1 && argv[1][0] != '-') {
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands({})) known = known || sub->get_name() == argv[1];
    if (!known) {
      std::cerr << "zhf: unknown command '" << argv[1] << "' (see zhf --help)\n";
      return kExitUsage;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "zhf: " << e.what() << " (see zhf --help)\n";
    return kExitUsage;
  }
  try {
    return action();
  } catch (const UsageError& e) {
    std::cerr << "zhf: " << e.what() << "\n";
    return kExitUsage;
  } catch (const zhf::io::InputError& e) {
    std::cerr << "zhf: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const zhf::io::OutputError& e) {
    std::cerr << "zhf: " << e.what() << "\n";
    return kExitOutput;
  } catch (const std::exception& e) {
    std::cerr << "zhf: internal error: " << e.what() << "\n";
    return kExitFailure;
  }
}
