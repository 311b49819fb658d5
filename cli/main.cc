// zhf: sparse zonal-harmonic factorisation of SH rotation. Thin front end over the libraries.
#include <algorithm>
#include <iostream>
#include <new>
#include <string>

#include "commands.h"
#include "options.h"
#include "zhf/dispatch/isa.h"
#include "zhf/dispatch/rotator.h"
#include "zhf/runtime/limits.h"
#include "zhf/io/errors.h"
#include "zhf/io/signals.h"

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

// One line on stderr. zhf's messages quote inputs as short escaped excerpts, but a path, or an
// option's text in CLI11's messages, may still hold control characters or be huge: those are
// escaped, and the line is cut at 1000 bytes.
int fail(int code, const std::string& message) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string line = "zhf: ";
  for (char c : message) {
    if (line.size() > 1000) {
      line += "...";
      break;
    }
    const unsigned char u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) {
      line += "\\x";
      line += kHex[u >> 4];
      line += kHex[u & 15];
    } else {
      line += c;
    }
  }
  std::cerr << line << "\n";
  return code;
}

// "zhf rotate --help" for an error inside a command, "zhf needlets tables --help" inside a
// subcommand, "zhf --help" otherwise.
std::string help_command(CLI::App& app, int argc, char** argv) {
  std::string command = "zhf";
  CLI::App* level = &app;
  for (int i = 1; i < argc && argv[i][0] != '-'; ++i) {
    CLI::App* sub = nullptr;
    for (CLI::App* s : level->get_subcommands({}))
      if (s->get_name() == argv[i]) sub = s;
    if (!sub) break;
    command += " " + sub->get_name();
    level = sub;
  }
  return command + " --help";
}

// "order N: float P, double Q" lines for the orders 1..zxzxz's limit where the choice can change.
std::string kernels_by_order() {
  std::string lines;
  for (int order = 1; order <= zhf::runtime::kMaxZxzxzOrder; order = order < 16 ? order + 1 : 2 * order)
    lines += "\norder " + std::to_string(order) + ": float " + zhf::dispatch::Rotator<float>::make(order).path() + ", double " +
             zhf::dispatch::Rotator<double>::make(order).path();
  return lines;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace zhf::cli;
  const zhf::io::InterruptGuard interrupts;
  // The instruction-set path every rotation of this run takes: a wrong ZHF_ISA is refused first.
  std::string isa;
  try {
    isa = zhf::dispatch::isa_name(zhf::dispatch::active_isa());
  } catch (const std::invalid_argument& e) {
    return fail(kExitUsage, e.what());
  }
  CLI::App app{"zhf " ZHF_VERSION ": fast real spherical-harmonic rotation by sparse zonal-harmonic factorisation"};
  // --version --verbose: the kernels each order takes on that path, as zhf::dispatch picks them.
  std::string version = "zhf " ZHF_VERSION " (rotation path " + isa + ")";
  if (std::any_of(argv + 1, argv + argc, [](const char* a) { return std::string(a) == "--verbose"; })) version += kernels_by_order();
  app.set_version_flag("--version", version);
  app.add_flag("--verbose", "With --version: the kernels each order takes, in float and double");
  app.require_subcommand(1);
  Action action;
  const std::string command = recorded_command(argc, argv);
  add_candidates_command(app, action);
  add_optimize_command(app, action, command);
  add_codegen_commands(app, action, command);
  add_verify_command(app, action);
  add_analyze_command(app, action);
  add_bench_command(app, action);
  add_rotate_command(app, action);
  add_splat_command(app, action);
  add_product_command(app, action);
  add_designs_command(app, action);
  add_frame_command(app, action);
  add_needlets_command(app, action, command);
  add_project_command(app, action);
  if (argc > 1 && argv[1][0] != '-') {
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands({})) known = known || sub->get_name() == argv[1];
    if (!known) return fail(kExitUsage, "unknown command '" + zhf::io::excerpt(argv[1]) + "' (see zhf --help)");
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
    return fail(kExitUsage, std::string(e.what()) + " (see " + help_command(app, argc, argv) + ")");
  }
  try {
    check_old_spellings();
    const int code = action();
    // A signal after the last output was committed still ends the run as an interrupted one.
    if (zhf::io::interrupt_requested().load()) {
      std::cerr << "zhf: interrupted after its outputs were written\n";
      return zhf::io::interrupted_exit_code();
    }
    return code;
  } catch (const zhf::io::Interrupted&) {
    // Which outputs changed: none, unless a commit the interrupt could not stop (or asked for) ran.
    std::cerr << zhf::io::interrupted_message() << "\n";
    return zhf::io::interrupted_exit_code();
  } catch (const UsageError& e) {
    return fail(kExitUsage, e.what());
  } catch (const zhf::io::InputError& e) {
    return fail(kExitBadInput, e.what());
  } catch (const zhf::io::OutputError& e) {
    return fail(kExitOutput, e.what());
  } catch (const std::bad_alloc&) {
    return fail(kExitFailure, "out of memory");
  } catch (const std::exception& e) {
    return fail(kExitFailure, std::string("internal error: ") + e.what());
  }
}
