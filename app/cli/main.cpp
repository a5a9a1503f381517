// motionstyle-cli: command dispatch and error-to-exit-code mapping only; the work is done by core.
#include <algorithm>
#include <exception>
#include <iostream>

#include "cli_args.h"
#include "commands.h"
#include "common/allocator_tuning.h"
#include "failure_report.h"

namespace {

void printUsage(std::ostream& out) {
  out << "usage: motionstyle-cli <command> [options]\n\n"
         "Fast neural style transfer for motion capture (Holden et al. 2017).\n\ncommands:\n";
  for (const auto& command : motionstyle::cli::commands())
    out << "  " << command.name << std::string(20 - std::min<std::size_t>(std::string(command.name).size(), 19), ' ')
        << command.summary << "\n";
  out << "\nRun 'motionstyle-cli <command> --help' for a command's options.\n"
         "Former names still work: train-ae (train-loss-network), --ae (--loss-network), the shipped\n"
         "network 'autoencoder' (loss_network).\n"
         "Exit codes: 0 ok, 2 bad input (message names the file and line) or an output that cannot or\n"
         "must not be written (an input, a folder, a read-only place: checked before any work starts),\n"
         "1 internal error,\n"
         "130 interrupted (Ctrl-C; a training run keeps its last checkpoint).\n";
}

}  // namespace

int main(int argc, char** argv) {
  using namespace motionstyle;
  restartWithHugePages(argv);  // allocator_tuning.h
  keepLargeAllocationsInHeap();
  const std::vector<std::string> all(argv + 1, argv + argc);
  if (all.empty() || all[0] == "--help" || all[0] == "-h" || all[0] == "help") {
    printUsage(all.empty() ? std::cerr : std::cout);
    return all.empty() ? 2 : 0;
  }
  if (all[0] == "--version") {
    std::cout << "motionstyle-cli " << MOTIONSTYLE_VERSION << "\n";
    return 0;
  }
  const cli::Command* command = nullptr;
  for (const auto& candidate : cli::commands())
    if (all[0] == candidate.name || (candidate.old_name && all[0] == candidate.old_name)) command = &candidate;
  if (!command) {
    std::cerr << "motionstyle-cli: unknown command '" << all[0] << "'\n\n";
    printUsage(std::cerr);
    return 2;
  }
  const cli::Args args(all.begin() + 1, all.end());
  for (const std::string& arg : args)
    if (arg == "--help" || arg == "-h") {
      std::cout << command->help;
      return 0;
    }
  try {
    return command->run(args);
  } catch (...) {
    return cli::reportFailure(std::current_exception(), command->name);
  }
}
