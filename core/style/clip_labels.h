#pragma once
// Content and style labels of a clip, read from its file name.
//
// Rules (applied to the file name without directory and extension, compared in lower case):
//   1. Bandai Namco datasets: "dataset-<n>_<content>_<style>_<take>", e.g.
//        dataset-2_walk-turn-left_elderly_012.bvh -> content "walk-turn-left", style "elderly"
//        dataset-1_walk_old_001.bvh               -> content "walk",           style "old"
//      <content> and <style> are letters, digits and '-', starting with a letter; <take> is digits.
//   2. Anything else: the content label is the FIRST ALPHABETIC WORD of the name (the first maximal run
//      of the letters a-z), and there is no style label:
//        walk_fast.bvh -> "walk",   cmu_131_01.bvh -> "cmu",   Zombie-Run2.bvh -> "zombie".
//      A name without any letter ("131_01.bvh") has the empty content label.
// The content label decides which style clip a content clip is paired with during style training
// (style_pairing.h): a style clip pairs with the content clips that share its own content label.

#include <filesystem>
#include <string>

namespace motionstyle::style {

struct ClipLabels {
  std::string content;  // e.g. "walk"; empty when the name has no letters
  std::string style;    // e.g. "elderly"; empty unless the name follows the Bandai convention
  bool operator==(const ClipLabels&) const = default;
};

ClipLabels parseClipLabels(const std::filesystem::path& file);

}  // namespace motionstyle::style
