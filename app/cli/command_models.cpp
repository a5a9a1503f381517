// motionstyle-cli models: the networks shipped in <resources>/models (common/resource_paths.h), and
// resolveNetworkArgument(), which lets every network option take a shipped network's bare name
// (--net elderly, --loss-network loss_network). Names, paths and messages are printed as safe text
// (common/text_safety.h): a file name must not drive the terminal or break the JSON.
#include <algorithm>
#include <iostream>
#include <nlohmann/json.hpp>
#include <system_error>

#include "cli_args.h"
#include "commands.h"
#include "common/errors.h"
#include "common/resource_paths.h"
#include "common/text_safety.h"
#include "nn/network_file.h"

namespace motionstyle::cli {
namespace {

struct ShippedNetwork {
  std::string name;
  std::filesystem::path file;
  std::string kind;  // "loss_network" or "style"
  int epochs = 0;
  std::vector<std::string> style_clips;
  std::string error;  // non-empty: the file could not be read
};

ShippedNetwork describeShipped(const std::filesystem::path& file) {
  ShippedNetwork network;
  network.name = safeText(file.stem().string());
  network.file = file;
  try {
    const nn::NetworkMetadata metadata = [&] {
      if (nn::networkFileKind(file) == nn::NetworkKind::Style) {
        network.kind = "style";
        return nn::loadStyleModel(file).metadata;
      }
      network.kind = "loss_network";
      return nn::loadLossNetwork(file).metadata;
    }();
    network.epochs = metadata.training.epochs;
    for (const nn::StyleClipRef& clip : metadata.style_clips) network.style_clips.push_back(safeText(clip.name));
  } catch (const InputError& error) {
    network.error = safeLines(error.what());
  }
  return network;
}

std::string joined(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
  return text.empty() ? "-" : text;
}

}  // namespace

std::filesystem::path resolveNetworkArgument(const std::string& argument) {
  const std::string value = argument == kFormerShippedLossNetworkName ? kShippedLossNetworkName : argument;
  std::error_code error;
  if (std::filesystem::exists(value, error) || !isValidNetworkName(value)) return value;
  const ResourceSearch search = currentResourceSearch();
  const std::optional<std::filesystem::path> resources = findResourceDirectory(search);
  if (resources)
    if (auto file = shippedNetworkFile(*resources, value)) return *file;
  std::string shipped;
  if (resources)
    for (const std::filesystem::path& file : shippedNetworkFiles(*resources))
      shipped += (shipped.empty() ? "" : ", ") + file.stem().string();
  throw InputError(value, 0,
                   "no such file, and no shipped network of that name (" +
                       (resources ? "shipped: " + (shipped.empty() ? std::string("none") : shipped) + " in " +
                                        (*resources / "models").string()
                                  : describeResourceLookup(search)) +
                       ")");
}

int runModels(const Args& args) {
  const ParsedArgs parsed = parseArgs(args, {{"json", false}});
  if (!parsed.positional.empty()) throw UsageError("models takes no arguments");
  const ResourceSearch search = currentResourceSearch();
  const std::optional<std::filesystem::path> resources = findResourceDirectory(search);
  if (!resources) {
    std::cerr << "motionstyle-cli models: " << describeResourceLookup(search) << "\n";
    return 1;
  }
  std::vector<ShippedNetwork> networks;
  for (const std::filesystem::path& file : shippedNetworkFiles(*resources)) networks.push_back(describeShipped(file));
  bool all_readable = true;
  for (const ShippedNetwork& network : networks) all_readable = all_readable && network.error.empty();

  if (parsed.has("json")) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const ShippedNetwork& n : networks) {
      nlohmann::ordered_json entry = {{"name", n.name}, {"file", safeText(n.file.string())}};
      if (!n.error.empty()) {
        entry["error"] = n.error;
      } else {
        entry["kind"] = n.kind;
        entry["epochs"] = n.epochs;
        entry["style_clips"] = n.style_clips;
      }
      list.push_back(std::move(entry));
    }
    std::cout << nlohmann::ordered_json{{"resources", safeText(resources->string())}, {"networks", list}}.dump(
                     2, ' ', false, nlohmann::ordered_json::error_handler_t::replace)
              << "\n";
    return all_readable ? 0 : 2;
  }

  std::cout << "resources: " << safeText(resources->string()) << "\n";
  if (networks.empty()) {
    std::cout << "no shipped networks in " << safeText((*resources / "models").string())
              << " (train your own: motionstyle-cli train-loss-network, train-style)\n";
    return 0;
  }
  size_t width = 4;
  for (const ShippedNetwork& n : networks) width = std::max(width, n.name.size());
  auto padded = [](const std::string& text, size_t size) {
    return text + std::string(std::max(size, text.size()) - text.size() + 2, ' ');
  };
  std::cout << padded("name", width) << padded("kind", 14) << padded("epochs", 6) << "style clips\n";
  for (const ShippedNetwork& n : networks) {
    if (!n.error.empty()) {
      std::cout << padded(n.name, width) << "UNREADABLE: " << n.error << "\n";
      continue;
    }
    std::cout << padded(n.name, width) << padded(n.kind, 14) << padded(std::to_string(n.epochs), 6)
              << joined(n.style_clips) << "\n";
  }
  for (const ShippedNetwork& n : networks)
    if (n.kind == "style") {
      std::cout << "\nUse a name wherever a network file is expected, e.g. motionstyle-cli stylize --net " << n.name
                << " IN.bvh --out OUT.bvh\n";
      break;
    }
  return all_readable ? 0 : 2;
}

std::filesystem::path lossNetworkArgument(const ParsedArgs& parsed) {
  return resolveNetworkArgument(parsed.value("loss-network").value_or(kShippedLossNetworkName));
}

}  // namespace motionstyle::cli
