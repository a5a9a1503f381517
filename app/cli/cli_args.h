#pragma once
// A small, strict command-line parser shared by the motionstyle-cli commands.
// Options are "--name value" or "--name=value"; flags are "--name". Unknown options are errors.

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "common/errors.h"

namespace motionstyle::cli {

// A usage mistake: the CLI prints it with the command's help hint and exits with code 2.
class UsageError : public Error {
 public:
  using Error::Error;
};

// The values a numeric option accepts: [min, max], open at either end where asked ("(0, 1]").
struct Range {
  double min;
  double max;
  bool min_open = false;
  bool max_open = false;
};

// Ranges shared by the commands' numeric options, so that one option means the same everywhere.
inline constexpr Range kOutputFpsRange{0.0, 1000.0, /*min_open=*/true};  // --fps, frames per second
inline constexpr Range kLearningRateRange{0.0, 1.0, /*min_open=*/true};  // --lr: Adam diverges far below 1
inline constexpr Range kLossWeightRange{0.0, 1e6};  // loss weights: beyond, float losses overflow (3e38)
inline constexpr int kMaxEpochs = 100000;

// Old option names kept working after a rename (one name per idea: "loss network" for the autoencoder).
struct OptionAlias {
  const char* old_name;  // without the leading "--"
  const char* name;
};
inline constexpr OptionAlias kOptionAliases[] = {{"ae", "loss-network"}};

// The option's current name: `name` itself, or what an alias in kOptionAliases stands for.
std::string canonicalOptionName(const std::string& name);

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
  // The option as a number (parseDecimal) or integer, `fallback` when absent. UsageError naming the
  // option when it is not one, and with a range when it lies outside it ("--lr must be in (0, 1]").
  double number(const std::string& name, double fallback) const;
  double number(const std::string& name, double fallback, const Range& range) const;
  int integer(const std::string& name, int fallback) const;
  int integer(const std::string& name, int fallback, int min, int max) const;

 private:
  friend ParsedArgs parseArgs(const std::vector<std::string>&, const std::vector<OptionSpec>&);
  std::map<std::string, std::vector<std::string>> values_;
};

// A decimal number as a user types it: [+|-]digits[.digits][(e|E)[+|-]digits], or with the digits only
// after the point (".5"); the whole text, finite, within double range. nullopt for anything else,
// notably what std::stod would take but nobody means: hex ("0x10"), "inf", "nan", blanks around it
// (" 60"), trailing garbage ("60fps").
std::optional<double> parseDecimal(std::string_view text);

// The value of --unit (a length unit: cm, m, mm, inch, ft, dm or cmu), nullopt when absent.
// UsageError listing the known units for any other name.
std::optional<std::string> lengthUnit(const ParsedArgs& parsed);

// Throws UsageError on an unknown option, a missing value or a repeated non-repeatable option.
ParsedArgs parseArgs(const std::vector<std::string>& args, const std::vector<OptionSpec>& specs);

}  // namespace motionstyle::cli
