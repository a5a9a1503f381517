#include "cli_args.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <system_error>

#include "features/space_convention.h"

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

namespace {

std::string describeRange(const Range& range) {
  auto bound = [](double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return std::string(text);
  };
  return std::string(range.min_open ? "(" : "[") + bound(range.min) + ", " + bound(range.max) + (range.max_open ? ")" : "]");
}

bool inRange(double value, const Range& range) {
  const bool above_min = range.min_open ? value > range.min : value >= range.min;
  const bool below_max = range.max_open ? value < range.max : value <= range.max;
  return above_min && below_max;
}

constexpr bool isDigit(char c) { return c >= '0' && c <= '9'; }

}  // namespace

std::optional<double> parseDecimal(std::string_view text) {
  // The shape first, so that from_chars' own extensions (inf, nan, hex with chars_format::hex) never apply.
  std::size_t i = 0;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  const std::size_t digits_start = i;
  while (i < text.size() && isDigit(text[i])) ++i;
  bool any_digit = i > digits_start;
  if (i < text.size() && text[i] == '.') {
    const std::size_t fraction_start = ++i;
    while (i < text.size() && isDigit(text[i])) ++i;
    any_digit = any_digit || i > fraction_start;
  }
  if (!any_digit) return std::nullopt;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    const std::size_t exponent_start = i;
    while (i < text.size() && isDigit(text[i])) ++i;
    if (i == exponent_start) return std::nullopt;
  }
  if (i != text.size()) return std::nullopt;
  const char* begin = text.data() + (text[0] == '+' ? 1 : 0);  // from_chars takes no '+'
  double value = 0.0;
  const auto [end, error] = std::from_chars(begin, text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

double ParsedArgs::number(const std::string& name, double fallback) const {
  auto v = value(name);
  if (!v) return fallback;
  const std::optional<double> parsed = parseDecimal(*v);
  if (!parsed) throw UsageError("--" + name + " expects a decimal number, got '" + *v + "'");
  return *parsed;
}

double ParsedArgs::number(const std::string& name, double fallback, const Range& range) const {
  const double parsed = number(name, fallback);
  if (has(name) && !inRange(parsed, range))
    throw UsageError("--" + name + " must be in " + describeRange(range) + ", got '" + *value(name) + "'");
  return parsed;
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

int ParsedArgs::integer(const std::string& name, int fallback, int min, int max) const {
  const int parsed = integer(name, fallback);
  if (has(name) && (parsed < min || parsed > max))
    throw UsageError("--" + name + " must be in [" + std::to_string(min) + ", " + std::to_string(max) + "], got '" +
                     *value(name) + "'");
  return parsed;
}

std::optional<std::string> lengthUnit(const ParsedArgs& parsed) {
  std::optional<std::string> unit = parsed.value("unit");
  if (unit && !centimetresPerUnit(*unit))
    throw UsageError("--unit must be one of " + knownUnitNames() + ", not '" + *unit + "'");
  return unit;
}

std::string canonicalOptionName(const std::string& name) {
  for (const OptionAlias& alias : kOptionAliases)
    if (name == alias.old_name) return alias.name;
  return name;
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
    name = canonicalOptionName(name);
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
