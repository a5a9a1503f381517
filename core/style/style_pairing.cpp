#include "style/style_pairing.h"

#include <set>

#include "common/errors.h"
#include "style/clip_labels.h"

namespace motionstyle::style {

StyleSource parseStyleSource(const std::string& text) {
  const std::size_t equals = text.find('=');
  if (equals != std::string::npos && equals > 0) {
    const std::string label = text.substr(0, equals);
    bool is_label = true;
    for (char c : label)
      is_label = is_label && ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_');
    if (is_label && equals + 1 < text.size()) {
      std::string lower = label;
      for (char& c : lower)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
      return {lower, text.substr(equals + 1)};
    }
  }
  return {std::nullopt, text};
}

std::map<std::string, int> styleLabelTable(const std::vector<StyleSource>& styles) {
  std::map<std::string, int> table;
  for (std::size_t i = 0; i < styles.size(); ++i)  // explicit labels first: they win
    if (styles[i].label) table.emplace(*styles[i].label, static_cast<int>(i));
  for (std::size_t i = 0; i < styles.size(); ++i)
    if (!styles[i].label) table.emplace(parseClipLabels(styles[i].file).content, static_cast<int>(i));
  return table;
}

std::vector<int> pairStyles(const std::vector<std::string>& content_labels, const std::vector<StyleSource>& styles) {
  if (styles.empty()) throw InputError("", 0, "no style clip given (--style CLIP.bvh or --style LABEL=CLIP.bvh)");
  const std::map<std::string, int> table = styleLabelTable(styles);
  int fallback = -1;
  for (std::size_t i = 0; i < styles.size() && fallback < 0; ++i)
    if (!styles[i].label) fallback = static_cast<int>(i);
  std::vector<int> pairing;
  std::set<std::string> lacking;
  for (const std::string& label : content_labels) {
    const auto found = table.find(label);
    const int style = found != table.end() ? found->second : fallback;
    if (style < 0) lacking.insert(label.empty() ? "(no label)" : label);
    pairing.push_back(style);
  }
  if (!lacking.empty()) {
    std::string list;
    for (const std::string& label : lacking) list += (list.empty() ? "" : ", ") + label;
    throw InputError(styles.front().file.string(), 0,
                     "no style clip for the content label(s): " + list +
                         " (give --style LABEL=CLIP.bvh for each, or a plain --style CLIP.bvh as the default)");
  }
  return pairing;
}

std::vector<int> pairTargets(const std::vector<std::string>& content_labels, const std::vector<std::string>& target_labels,
                             const std::string& source) {
  int fallback = -1;
  for (std::size_t i = 0; i < target_labels.size() && fallback < 0; ++i)
    if (target_labels[i].empty()) fallback = static_cast<int>(i);
  std::vector<int> pairing;
  std::set<std::string> lacking;
  for (const std::string& label : content_labels) {
    int target = fallback;
    for (std::size_t i = 0; i < target_labels.size(); ++i)
      if (!label.empty() && target_labels[i] == label) target = static_cast<int>(i);
    if (target < 0) lacking.insert(label.empty() ? "(no label)" : label);
    pairing.push_back(target);
  }
  if (!lacking.empty()) {
    std::string list;
    for (const std::string& label : lacking) list += (list.empty() ? "" : ", ") + label;
    throw InputError(source, 0, "the network's stored style targets cover no default and not the content label(s): " +
                                    list + " (give --style LABEL=CLIP.bvh for them)");
  }
  return pairing;
}

}  // namespace motionstyle::style
