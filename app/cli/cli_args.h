#pragma once
// A small, strict command-line parser shared by the motionstyle-cli commands.
// Options are "--name value" or "--name=value"; flags are "--name". Unknown options are errors.

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace motionstyle::cli {

// A usage mistake: the CLI prints it with the command's help hint and exits with code 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct OptionSpec {
  std::string name;         // without the leading "--"
  bool takes_value = true;  // false: a flag
  bool repeatable = false;  // may appear more than once (values collected in order)
};

class ParsedArgs {
 public:
  std::vector<std::string> positional;

  bool has(const std::string& name) const { return values_.count(name) > 0; }
  std::optional<std::string> value(const std::string& name) const;
  const std::vector<std::string>& values(const std::string& name) const;
  std::string required(const std::string& name) const;
  double number(const std::string& name, double fallback) const;
  int integer(const std::string& name, int fallback) const;

 private:
  friend ParsedArgs parseArgs(const std::vector<std::string>&, const std::vector<OptionSpec>&);
  std::map<std::string, std::vector<std::string>> values_;
};

// Throws UsageError on an unknown option, a missing value or a repeated non-repeatable option.
ParsedArgs parseArgs(const std::vector<std::string>& args, const std::vector<OptionSpec>& specs);

}  // namespace motionstyle::cli
