#pragma once
// Which style clip each content clip is trained (or evaluated) against: the paper pairs "all training
// clips where the content contains running ... with the angry run style, and all content clips
// containing walking with the angry walk style".
//
// A StyleSource is a style clip with an optional explicit label ("--style walk=angry_walk.bvh").
//   - An explicit label pairs that clip with the content clips of exactly that label.
//   - A clip without an explicit label pairs by its OWN content label from its file name
//     (clip_labels.h: dataset-1_walk_angry_001.bvh pairs with the "walk" content clips).
//   - The FIRST clip without an explicit label is also the DEFAULT: content labels that nothing else
//     matches use it. With only labelled clips there is no default, and content labels left without a
//     style clip are an error that lists them.
// Explicit labels win over file-name labels; between two clips claiming one label, the first given wins.

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace motionstyle::style {

struct StyleSource {
  std::optional<std::string> label;  // explicit content label, or none (use the file name)
  std::filesystem::path file;
};

// Parses "LABEL=PATH" (label = letters, digits, '-', '_' before the first '=') or a plain path.
// A path that itself contains '=' after a non-label prefix is taken as a plain path.
StyleSource parseStyleSource(const std::string& text);

// pairing[i] = index into `styles` for content label content_labels[i]. Throws InputError listing the
// labels without a style clip (when there is no default) or for an empty `styles`.
std::vector<int> pairStyles(const std::vector<std::string>& content_labels, const std::vector<StyleSource>& styles);

// The same rule against stored style targets (nn::StyleTarget: a label per target, "" = the default):
// pairing[i] = index into `target_labels` of the target with label content_labels[i], else of the
// default. Throws InputError naming `source` and listing the labels left without a target.
std::vector<int> pairTargets(const std::vector<std::string>& content_labels, const std::vector<std::string>& target_labels,
                             const std::string& source);

// The label -> style index table (before the default is applied), for messages and the network file.
std::map<std::string, int> styleLabelTable(const std::vector<StyleSource>& styles);

}  // namespace motionstyle::style
