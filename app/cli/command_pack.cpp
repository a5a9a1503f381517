// motionstyle-cli pack: rewrites a network file in the current format with its weights in f16 or f32
// (NETWORK_FORMAT.md). f16 halves the size of a network; the shipped networks use it.
#include <cstdio>
#include <iostream>

#include "cli_args.h"
#include "commands.h"
#include "common/output_paths.h"
#include "nn/network_file.h"

namespace motionstyle::cli {
namespace {

nn::WeightPrecision parsePrecision(const std::string& text) {
  if (text == "f16") return nn::WeightPrecision::F16;
  if (text == "f32") return nn::WeightPrecision::F32;
  throw UsageError("--precision must be f16 or f32, not '" + text + "'");
}

std::string summary(const nn::NetworkFileInfo& info) {
  char text[96];
  std::snprintf(text, sizeof text, "format %u, %s, %.2f MB", static_cast<unsigned>(info.format_version),
                nn::weightPrecisionName(info.precision), static_cast<double>(info.bytes) / 1e6);
  return text;
}

}  // namespace

int runPack(const Args& args) {
  const ParsedArgs parsed = parseArgs(args, {{"out"}, {"precision"}});
  if (parsed.positional.size() != 1) throw UsageError("pack needs exactly one input network file IN.net");
  const std::filesystem::path input = resolveNetworkArgument(parsed.positional[0]);  // or a shipped name
  const std::filesystem::path output = parsed.required("out");
  const nn::WeightPrecision precision = parsePrecision(parsed.value("precision").value_or("f16"));

  checkOutputPaths({}, {{output, "--out"}});  // OUT may be IN itself: pack rewrites a file in place
  const nn::NetworkFileInfo before = nn::networkFileInfo(input);  // full validation
  if (before.kind == nn::NetworkKind::Style)
    nn::saveStyleModel(nn::loadStyleModel(input), output, precision);
  else
    nn::saveLossNetwork(nn::loadLossNetwork(input), output, precision);
  const nn::NetworkFileInfo after = nn::networkFileInfo(output);  // it reads back
  std::cout << input.string() << " (" << summary(before) << ") -> " << output.string() << " (" << summary(after)
            << ")\n";
  return 0;
}

}  // namespace motionstyle::cli
