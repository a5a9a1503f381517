#pragma once
// The one translation of a failure into a message on stderr and an exit code (README "Exit codes"):
// 2 for the user's input, output or usage (UsageError adds the command's --help hint), 1 for a
// diverged training or an internal error, 130 for an interrupted one. main() calls it for a command,
// batch mode for each clip it could not write. Messages name the user's files: safeLines keeps a
// file name from driving the terminal.

#include <exception>
#include <string>

namespace motionstyle::cli {

int reportFailure(const std::exception_ptr& failure, const std::string& command);

}  // namespace motionstyle::cli
