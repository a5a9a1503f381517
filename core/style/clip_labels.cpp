#include "style/clip_labels.h"

#include <cctype>
#include <regex>

namespace motionstyle::style {
namespace {

std::string lowerCase(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

bool isLetter(char c) { return (c >= 'a' && c <= 'z'); }

}  // namespace

ClipLabels parseClipLabels(const std::filesystem::path& file) {
  const std::string stem = lowerCase(file.stem().string());
  static const std::regex bandai(R"(^dataset-\d+_([a-z][a-z0-9-]*)_([a-z][a-z0-9-]*)_\d+$)");
  std::smatch match;
  if (std::regex_match(stem, match, bandai)) return {match[1].str(), match[2].str()};

  ClipLabels labels;
  std::size_t begin = 0;
  while (begin < stem.size() && !isLetter(stem[begin])) ++begin;
  std::size_t end = begin;
  while (end < stem.size() && isLetter(stem[end])) ++end;
  labels.content = stem.substr(begin, end - begin);
  return labels;
}

}  // namespace motionstyle::style
