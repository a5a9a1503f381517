#pragma once
// The motionstyle-cli commands. Each takes the arguments after its name and returns the exit code:
// 0 ok, 2 bad input or usage (message on stderr naming the file and line), 1 internal error.
// Exceptions propagate to main(), which maps them to those codes.

#include <filesystem>
#include <string>
#include <vector>

namespace motionstyle::style {
struct StylizedClip;
}

namespace motionstyle::cli {

class ParsedArgs;
using Args = std::vector<std::string>;

struct Command {
  const char* name;
  const char* summary;
  const char* help;  // full --help text
  int (*run)(const Args& args);
  const char* old_name = nullptr;  // a former name that still runs it ("train-ae"), or none
};

const std::vector<Command>& commands();

int runInfo(const Args& args);
int runConvert(const Args& args);
int runTrainLossNetwork(const Args& args);
int runTrainStyle(const Args& args);
int runAdapt(const Args& args);
int runRemember(const Args& args);
int runStylize(const Args& args);
int runTransfer(const Args& args);
int runEval(const Args& args);

int runCleanup(const Args& args);
int runPack(const Args& args);
int runModels(const Args& args);

// A network option's value as a file (command_models.cpp): VALUE itself when such a file exists or
// VALUE is not a bare name; otherwise the shipped <resources>/models/VALUE.net (common/resource_paths.h).
// Throws InputError naming VALUE and the shipped networks when a bare name matches neither.
std::filesystem::path resolveNetworkArgument(const std::string& value);

// --loss-network as a file (resolveNetworkArgument), the shipped loss network when it is not given:
// as in the app, a first training or adaptation needs nothing but clips.
std::filesystem::path lossNetworkArgument(const ParsedArgs& parsed);

}  // namespace motionstyle::cli
