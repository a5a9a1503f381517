#include "cli_args.h"

#include <charconv>
#include <cmath>

namespace motionstyle::cli {

std::optional<std::string> ParsedArgs::value(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end() || it->second.empty()) return std::nullopt;
  return it->second.back();
}

const std::vector<std::string>& ParsedArgs::values(const std::string& name) const {
  static const std::vector<std::string> empty;
  auto it = values_.find(name);
  return it == values_.end() ? empty : it->second;
}

std::string ParsedArgs::required(const std::string& name) const {
  auto v = value(name);
  if (!v) throw UsageError("missing required option --" + name);
  return *v;
}

double ParsedArgs::number(const std::string& name, double fallback) const {
  auto v = value(name);
  if (!v) return fallback;
  try {
    size_t used = 0;
    const double parsed = std::stod(*v, &used);
    if (used != v->size() || !std::isfinite(parsed)) throw std::invalid_argument("not finite");
    return parsed;
  } catch (const std::exception&) {
    throw UsageError("--" + name + " expects a number, got '" + *v + "'");
  }
}

int ParsedArgs::integer(const std::string& name, int fallback) const {
  auto v = value(name);
  if (!v) return fallback;
  int parsed = 0;
  const char* end = v->data() + v->size();
  auto [ptr, error] = std::from_chars(v->data(), end, parsed);
  if (error != std::errc() || ptr != end) throw UsageError("--" + name + " expects an integer, got '" + *v + "'");
  return parsed;
}

ParsedArgs parseArgs(const std::vector<std::string>& args, const std::vector<OptionSpec>& specs) {
  ParsedArgs parsed;
  bool options_done = false;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (options_done || arg.size() < 3 || arg.rfind("--", 0) != 0) {
      if (arg == "--") {
        options_done = true;
        continue;
      }
      parsed.positional.push_back(arg);
      continue;
    }
    std::string name = arg.substr(2);
    std::optional<std::string> inline_value;
    if (auto eq = name.find('='); eq != std::string::npos) {
      inline_value = name.substr(eq + 1);
      name = name.substr(0, eq);
    }
    const OptionSpec* spec = nullptr;
    for (const OptionSpec& s : specs)
      if (s.name == name) spec = &s;
    if (!spec) throw UsageError("unknown option --" + name);
    auto& slot = parsed.values_[name];
    if (!slot.empty() && !spec->repeatable) throw UsageError("option --" + name + " given more than once");
    if (!spec->takes_value) {
      if (inline_value) throw UsageError("option --" + name + " takes no value");
      slot.emplace_back("1");
      continue;
    }
    if (inline_value) {
      slot.push_back(*inline_value);
    } else {
      if (i + 1 >= args.size()) throw UsageError("option --" + name + " needs a value");
      slot.push_back(args[++i]);
    }
  }
  return parsed;
}

}  // namespace motionstyle::cli
