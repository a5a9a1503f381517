#include "mapping/mapping_file.h"

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <vector>

#include "common/atomic_file.h"
#include "common/errors.h"

namespace motionstyle {

namespace {

// A mapping file names 21 joints; anything near this size is not one, and is not read into memory.
constexpr std::uintmax_t kMaxMappingFileBytes = 1u << 20;

// 1-based line of the character at `offset` (the last line when the offset lies past the end).
int lineAt(std::string_view text, size_t offset) {
  offset = std::min(offset, text.size());
  if (offset == text.size() && offset > 0 && text[offset - 1] == '\n') --offset;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
}

// Where a JSON string literal appears in the text, searching from `from` (as an object key: followed by
// a ':'); npos when it is written with escapes we do not reproduce. Only points messages at a line.
size_t findLiteral(std::string_view text, const std::string& value, size_t from, bool as_key = false) {
  const std::string literal = nlohmann::json(value).dump();
  for (size_t at = text.find(literal, from); at != std::string_view::npos; at = text.find(literal, at + 1)) {
    if (!as_key) return at;
    const size_t next = text.find_first_not_of(" \t\r\n", at + literal.size());
    if (next != std::string_view::npos && text[next] == ':') return at;
  }
  return std::string_view::npos;
}

int lineOfKey(std::string_view text, const std::string& key, size_t from = 0) {
  const size_t at = findLiteral(text, key, from, true);
  return at == std::string_view::npos ? 0 : lineAt(text, at);
}

// nlohmann's message without its "[json.exception...] parse error at line L, column C: " prefix.
std::string parseErrorDetail(const nlohmann::json::parse_error& error) {
  const std::string what = error.what();
  const size_t column = what.find("column ");
  const size_t colon = column == std::string::npos ? std::string::npos : what.find(": ", column);
  return colon == std::string::npos ? what : what.substr(colon + 2);
}

std::string canonicalNameList() {
  std::string list;
  for (CanonicalJoint joint : kAllCanonicalJoints) list += (list.empty() ? "" : ", ") + std::string(canonicalJointName(joint));
  return list;
}

nlohmann::json parseJson(std::string_view text, const std::string& source) {
  // Repeated keys would silently keep the last value; the callback notices them.
  std::vector<std::set<std::string>> open_objects;
  std::string repeated_key;
  auto notice_repeats = [&](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    if (event == Event::object_start) open_objects.emplace_back();
    if (event == Event::object_end && !open_objects.empty()) open_objects.pop_back();
    if (event == Event::key && !open_objects.empty() && repeated_key.empty() &&
        !open_objects.back().insert(parsed.get<std::string>()).second)
      repeated_key = parsed.get<std::string>();
    return true;
  };
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(text.begin(), text.end(), notice_repeats, true, /*ignore_comments=*/true);
  } catch (const nlohmann::json::parse_error& error) {
    throw InputError(source, lineAt(text, error.byte > 0 ? error.byte - 1 : 0), "invalid JSON: " + parseErrorDetail(error));
  }
  if (!repeated_key.empty()) {
    const size_t first = findLiteral(text, repeated_key, 0, true);
    const size_t second =
        first == std::string_view::npos ? first : findLiteral(text, repeated_key, first + 1, true);
    throw InputError(source, second == std::string_view::npos ? 0 : lineAt(text, second),
                     "the key \"" + repeated_key + "\" appears twice");
  }
  return root;
}

}  // namespace

JointMapping parseJointMapping(std::string_view text, const Skeleton& skeleton, const std::string& source_name) {
  skeleton.validate();
  const nlohmann::json root = parseJson(text, source_name);
  if (!root.is_object())
    throw InputError(source_name, 1, "expected a JSON object with \"format\", \"version\" and \"joints\"");

  const auto format = root.find("format");
  if (format == root.end() || !format->is_string() || format->get<std::string>() != kJointMappingFormat)
    throw InputError(source_name, format == root.end() ? 1 : lineOfKey(text, "format"),
                     "expected \"format\": \"" + std::string(kJointMappingFormat) + "\"");
  const auto version = root.find("version");
  if (version == root.end() || !version->is_number_integer() || version->get<std::int64_t>() != kJointMappingVersion)
    throw InputError(source_name, version == root.end() ? 1 : lineOfKey(text, "version"),
                     "expected \"version\": " + std::to_string(kJointMappingVersion) +
                         " (this program reads joint mapping files of version 1 only)");
  const auto joints = root.find("joints");
  if (joints == root.end() || !joints->is_object())
    throw InputError(source_name, joints == root.end() ? 1 : lineOfKey(text, "joints"),
                     "expected \"joints\": an object from canonical joint names to the rig's joint names");

  const size_t joints_at = std::min(findLiteral(text, "joints", 0, true), text.size());
  JointMapping mapping;
  mapping.convention = "file:" + source_name;
  for (const auto& [key, value] : joints->items()) {
    const size_t key_at = findLiteral(text, key, joints_at, true);
    const int key_line = key_at == std::string_view::npos ? 0 : lineAt(text, key_at);
    const std::optional<CanonicalJoint> canonical = canonicalJointFromName(key);
    if (!canonical)
      throw InputError(source_name, key_line,
                       "unknown canonical joint \"" + key + "\" (expected one of " + canonicalNameList() + ")");
    if (mapping[*canonical] >= 0)
      throw InputError(source_name, key_line,
                       "\"" + key + "\" repeats " + std::string(canonicalJointName(*canonical)) + " (names ignore case)");
    if (!value.is_string())
      throw InputError(source_name, key_line, "expected the rig's joint name as a string for \"" + key + "\"");
    const std::string rig_name = value.get<std::string>();
    if (rig_name.empty())
      throw InputError(source_name, key_line,
                       "no rig joint given for " + std::string(canonicalJointName(*canonical)) +
                           ": fill in the name of the rig's joint (the comments above list them)");
    const int rig_joint = skeleton.find(rig_name);
    if (rig_joint < 0)
      throw InputError(source_name, key_line,
                       "the rig has no joint named \"" + rig_name + "\" (for " +
                           std::string(canonicalJointName(*canonical)) +
                           "; names are case-sensitive, End Sites are named \"<parent>_End\")");
    mapping[*canonical] = rig_joint;
  }
  if (const std::optional<std::string> problem = describeMappingProblem(mapping, skeleton))
    throw InputError(source_name, 0, "the joint mapping is unusable: " + *problem);
  return mapping;
}

JointMapping loadJointMapping(const std::filesystem::path& json, const Skeleton& skeleton) {
  const std::string source = json.string();
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(json, error);
  if (error) throw InputError(source, 0, "cannot read the joint mapping file: " + error.message());
  if (size > kMaxMappingFileBytes)
    throw InputError(source, 0, "the file has " + std::to_string(size) + " bytes; a joint mapping file is under 1 MiB");
  std::ifstream in(json, std::ios::binary);
  if (!in) throw InputError(source, 0, "cannot open the joint mapping file");
  std::string text(static_cast<size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad() || in.gcount() != static_cast<std::streamsize>(text.size()))
    throw InputError(source, 0, "cannot read the joint mapping file");
  return parseJointMapping(text, skeleton, source);
}

std::string formatJointMapping(const JointMapping& mapping, const Skeleton& skeleton) {
  if (const std::optional<std::string> problem = describeMappingProblem(mapping, skeleton))
    throw std::invalid_argument("cannot save the joint mapping: " + *problem);
  nlohmann::ordered_json joints = nlohmann::ordered_json::object();
  for (CanonicalJoint joint : kAllCanonicalJoints)
    joints[std::string(canonicalJointName(joint))] = skeleton.joints[static_cast<size_t>(mapping[joint])].name;
  nlohmann::ordered_json root;
  root["format"] = kJointMappingFormat;
  root["version"] = kJointMappingVersion;
  root["joints"] = std::move(joints);
  return root.dump(2) + "\n";
}

std::string formatJointMappingTemplate(const JointMapping& guess, const Skeleton& skeleton, const std::string& clip_name) {
  nlohmann::ordered_json joints = nlohmann::ordered_json::object();
  for (CanonicalJoint joint : kAllCanonicalJoints) {
    const int rig_joint = guess[joint];
    const bool found = rig_joint >= 0 && rig_joint < static_cast<int>(skeleton.joints.size());
    joints[std::string(canonicalJointName(joint))] = found ? skeleton.joints[static_cast<size_t>(rig_joint)].name : "";
  }
  const std::string missing = guess.missingNames();
  nlohmann::ordered_json root;
  root["format"] = kJointMappingFormat;
  root["version"] = kJointMappingVersion;
  root["joints"] = std::move(joints);
  std::string text = "// Joint mapping for " + clip_name + ": the rig's joint for each of the 21 canonical joints.\n";
  text += missing.empty() ? "// Every joint was found; check them.\n"
                          : "// Fill in the empty ones (" + missing + ") with joints of the rig listed below.\n";
  text += "// Each must hang below its canonical parent's joint; End Sites are named \"<parent>_End\".\n";
  text += "// Then use it: motionstyle-cli ... --mapping THIS_FILE, or in the app right-click the clip,\n";
  text += "// Load Mapping File.\n// The rig's joints:";
  std::string line;
  for (const Joint& joint : skeleton.joints) {
    const std::string& name = joint.name;  // an End Site's is "<parent>_End"
    if (line.size() + name.size() > 96) {
      text += line + "\n//";
      line.clear();
    }
    line += " " + name;
  }
  return text + line + "\n" + root.dump(2) + "\n";
}

void saveJointMapping(const JointMapping& mapping, const Skeleton& skeleton, const std::filesystem::path& json) {
  writeFileAtomically(json, formatJointMapping(mapping, skeleton));
}

JointMapping mapJoints(const Skeleton& skeleton, const std::string& source,
                       const std::optional<std::filesystem::path>& mapping_file) {
  if (mapping_file) return loadJointMapping(*mapping_file, skeleton);
  return mapJoints(skeleton, source);
}

}  // namespace motionstyle
