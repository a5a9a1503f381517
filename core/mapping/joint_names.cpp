#include "mapping/joint_names.h"

#include <cctype>

namespace motionstyle {

namespace {

bool isSeparator(char c) { return c == '_' || c == '-' || c == '.' || c == ' ' || c == '\t'; }
bool isUpper(char c) { return std::isupper(static_cast<unsigned char>(c)) != 0; }
bool isLower(char c) { return std::islower(static_cast<unsigned char>(c)) != 0; }
bool isDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }
char toLower(char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); }

std::string_view withoutNamespace(std::string_view name) {
  const size_t cut = name.find_last_of(":|");
  return cut == std::string_view::npos ? name : name.substr(cut + 1);
}

// Tokens that decorate a name without saying anything about the joint: 3ds Max's "Bip01", Mixamo's
// "mixamorig" when it arrives with '_' instead of ':', Blender's "DEF", Maya's "jnt".
bool isDecoration(const std::string& token) {
  auto startsWithThenDigits = [&](std::string_view prefix) {
    if (token.compare(0, prefix.size(), prefix) != 0) return false;
    for (size_t i = prefix.size(); i < token.size(); ++i)
      if (!isDigit(token[i])) return false;
    return true;
  };
  return startsWithThenDigits("bip") || startsWithThenDigits("mixamorig") || token == "def" ||
         token == "jnt" || token == "jt";
}

// Splits on separators and camel case ("LHipJoint" -> l, hip, joint; "UpperArm_L" -> upper, arm, l).
// Digits stay with the word before them ("Spine1", "Toe0", "Bip01").
std::vector<std::string> tokenize(std::string_view name) {
  std::vector<std::string> tokens;
  std::string current;
  auto flush = [&] {
    if (!current.empty()) tokens.push_back(current);
    current.clear();
  };
  for (size_t i = 0; i < name.size(); ++i) {
    const char c = name[i];
    if (isSeparator(c)) {
      flush();
      continue;
    }
    if (isUpper(c) && i > 0) {
      const char previous = name[i - 1];
      const bool after_lower = isLower(previous) || isDigit(previous);
      const bool acronym_end = isUpper(previous) && i + 1 < name.size() && isLower(name[i + 1]);
      if (after_lower || acronym_end) flush();
    }
    current.push_back(toLower(c));
  }
  flush();
  std::vector<std::string> kept;
  for (std::string& token : tokens)
    if (!isDecoration(token)) kept.push_back(std::move(token));
  // A name made only of decorations ("Bip01") is its own joint.
  return kept.empty() ? tokens : kept;
}

BodySide sideOfToken(const std::string& token) {
  if (token == "l" || token == "left") return BodySide::Left;
  if (token == "r" || token == "right") return BodySide::Right;
  return BodySide::Center;
}

std::string join(const std::vector<std::string>& tokens, size_t skip) {
  std::string joined;
  for (size_t i = 0; i < tokens.size(); ++i)
    if (i != skip) joined += tokens[i];
  return joined;
}

void addReading(std::vector<JointNameReading>& readings, BodySide side, std::string base) {
  if (base.empty()) return;
  for (const JointNameReading& existing : readings)
    if (existing.side == side && existing.base == base) return;
  readings.push_back({side, std::move(base)});
}

// "lefthand" / "handright" / "lhand" / "handl": a side glued to the flattened name's start or end.
void addGluedReadings(std::vector<JointNameReading>& readings, const std::string& flat) {
  struct Marker {
    std::string_view text;
    BodySide side;
  };
  constexpr Marker kWords[] = {{"left", BodySide::Left}, {"right", BodySide::Right}};
  constexpr Marker kLetters[] = {{"l", BodySide::Left}, {"r", BodySide::Right}};
  for (const auto* markers : {static_cast<const Marker*>(kWords), static_cast<const Marker*>(kLetters)}) {
    for (int m = 0; m < 2; ++m) {
      const Marker& marker = markers[m];
      if (flat.size() <= marker.text.size()) continue;
      if (flat.compare(0, marker.text.size(), marker.text) == 0)
        addReading(readings, marker.side, flat.substr(marker.text.size()));
      if (flat.compare(flat.size() - marker.text.size(), marker.text.size(), marker.text) == 0)
        addReading(readings, marker.side, flat.substr(0, flat.size() - marker.text.size()));
    }
  }
}

}  // namespace

std::vector<JointNameReading> readJointName(std::string_view name) {
  const std::vector<std::string> tokens = tokenize(withoutNamespace(name));
  std::vector<JointNameReading> readings;
  if (tokens.empty()) return readings;

  // 1. One explicit side token. Two of them ("L_R") say nothing reliable, so neither is used.
  size_t side_token = tokens.size();
  int side_tokens = 0;
  for (size_t i = 0; i < tokens.size(); ++i) {
    if (sideOfToken(tokens[i]) != BodySide::Center) {
      side_token = i;
      ++side_tokens;
    }
  }
  if (side_tokens == 1) addReading(readings, sideOfToken(tokens[side_token]), join(tokens, side_token));

  // 2. The whole name as a centre joint.
  const std::string flat = join(tokens, tokens.size());
  addReading(readings, BodySide::Center, flat);

  // 3. A side glued to a word.
  addGluedReadings(readings, flat);
  return readings;
}

std::string flattenJointName(std::string_view name) {
  return join(tokenize(withoutNamespace(name)), static_cast<size_t>(-1));
}

}  // namespace motionstyle
