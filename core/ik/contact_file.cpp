#include "ik/contact_file.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "common/atomic_file.h"
#include "common/errors.h"

namespace motionstyle {
namespace {

constexpr const char* kFormat = "motionstyle-contacts";
constexpr int kVersion = 1;
constexpr std::array<const char*, kContactCount> kTrackNames = {"LeftHeel", "LeftToe", "RightHeel", "RightToe"};
constexpr std::uintmax_t kMaxFileBytes = std::uintmax_t{256} << 20;  // 4 tracks of 50 M frames and then some

// 1-based line of byte `offset` in text.
int lineAt(std::string_view text, size_t offset) {
  offset = std::min(offset, text.size());
  int line = 1;
  for (size_t i = 0; i < offset; ++i)
    if (text[i] == '\n') ++line;
  return line;
}

// "key" with its quotes (built by appending: GCC 12's -Wrestrict misfires on "literal" + std::string).
std::string quoted(std::string_view key) {
  std::string result;
  result.reserve(key.size() + 2);
  result += '"';
  result += key;
  result += '"';
  return result;
}

// Line of the first quoted `key` after the first quoted `section` (or from the start); 0 when absent.
int lineOfKey(std::string_view text, std::string_view section, std::string_view key) {
  size_t from = 0;
  if (!section.empty()) {
    from = text.find(quoted(section));
    if (from == std::string_view::npos) return 0;
  }
  const size_t at = text.find(quoted(key), from);
  return at == std::string_view::npos ? 0 : lineAt(text, at);
}

// Parses one track string into column `label` of `out`. `alphabet` maps characters to values.
void readTrack(const nlohmann::json& value, int frames, bool overrides, Eigen::MatrixXi& out, int label,
               std::string_view text, const std::string& source) {
  const char* section = overrides ? "overrides" : "tracks";
  const std::string name = kTrackNames[static_cast<size_t>(label)];
  const int line = lineOfKey(text, section, name);
  if (!value.is_string())
    throw InputError(source, line, std::string(section) + "." + name + ": expected a string of one character per frame");
  const std::string& track = value.get_ref<const std::string&>();
  if (track.size() != static_cast<size_t>(frames))
    throw InputError(source, line, std::string(section) + "." + name + ": expected " + std::to_string(frames) +
                                       " characters (one per frame), got " + std::to_string(track.size()));
  for (int f = 0; f < frames; ++f) {
    const char c = track[static_cast<size_t>(f)];
    int v = 0;
    if (c == '0') v = 0;
    else if (c == '1') v = 1;
    else if (c == '.' && overrides) v = -1;
    else
      throw InputError(source, line, std::string(section) + "." + name + ": frame " + std::to_string(f) +
                                         ": expected " + (overrides ? "'.', '0' or '1'" : "'0' or '1'") + ", got '" +
                                         std::string(1, c) + "'");
    out(f, label) = v;
  }
}

void readSection(const nlohmann::json& root, const char* section, bool required, int frames, Eigen::MatrixXi& out,
                 std::string_view text, const std::string& source) {
  if (!root.contains(section)) {
    if (required) throw InputError(source, 0, std::string("expected a \"") + section + "\" object");
    return;
  }
  const nlohmann::json& tracks = root[section];
  if (!tracks.is_object())
    throw InputError(source, lineOfKey(text, "", section), std::string("\"") + section + "\": expected an object");
  for (const auto& [key, value] : tracks.items()) {
    bool known = false;
    for (const char* name : kTrackNames) known = known || key == name;
    if (!known)
      throw InputError(source, lineOfKey(text, section, key),
                       std::string(section) + ": unknown track \"" + key +
                           "\" (expected LeftHeel, LeftToe, RightHeel, RightToe)");
  }
  out = Eigen::MatrixXi::Constant(frames, kContactCount, required ? 0 : -1);
  for (int label = 0; label < kContactCount; ++label) {
    const char* name = kTrackNames[static_cast<size_t>(label)];
    if (!tracks.contains(name)) {
      if (required) throw InputError(source, lineOfKey(text, "", section), std::string(section) + ": missing track " + name);
      continue;
    }
    readTrack(tracks[name], frames, !required, out, label, text, source);
  }
}

}  // namespace

void ContactTracks::validate() const {
  if (!std::isfinite(fps) || !(fps > 0.0)) throw std::invalid_argument("contact tracks: fps must be positive");
  if (labels.cols() != kContactCount) throw std::invalid_argument("contact tracks: labels must have 4 columns");
  if ((labels.array() < 0).any() || (labels.array() > 1).any())
    throw std::invalid_argument("contact tracks: labels must be 0 or 1");
  if (overrides.size() > 0) {
    if (overrides.rows() != labels.rows() || overrides.cols() != kContactCount)
      throw std::invalid_argument("contact tracks: overrides must be empty or frames x 4 like the labels");
    if ((overrides.array() < -1).any() || (overrides.array() > 1).any())
      throw std::invalid_argument("contact tracks: overrides must be -1, 0 or 1");
  }
}

std::filesystem::path contactTracksPath(const std::filesystem::path& clip) {
  return std::filesystem::path(clip.string() + ".contacts.json");
}

std::string formatContactTracks(const ContactTracks& tracks) {
  tracks.validate();
  nlohmann::ordered_json json;
  json["format"] = kFormat;
  json["version"] = kVersion;
  json["fps"] = tracks.fps;
  json["frames"] = tracks.labels.rows();
  auto track = [](const Eigen::MatrixXi& values, int label) {
    std::string text(static_cast<size_t>(values.rows()), '.');
    for (Eigen::Index f = 0; f < values.rows(); ++f) {
      const int v = values(f, label);
      text[static_cast<size_t>(f)] = v < 0 ? '.' : (v == 0 ? '0' : '1');
    }
    return text;
  };
  for (int label = 0; label < kContactCount; ++label)
    json["tracks"][kTrackNames[static_cast<size_t>(label)]] = track(tracks.labels, label);
  if (tracks.overrides.size() > 0)
    for (int label = 0; label < kContactCount; ++label)
      json["overrides"][kTrackNames[static_cast<size_t>(label)]] = track(tracks.overrides, label);
  return json.dump(2) + "\n";
}

void saveContactTracks(const ContactTracks& tracks, const std::filesystem::path& file) {
  writeFileAtomically(file, formatContactTracks(tracks));
}

ContactTracks parseContactTracks(std::string_view text, const std::string& source) {
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& error) {
    throw InputError(source, lineAt(text, error.byte > 0 ? error.byte - 1 : 0),
                     std::string("expected valid JSON: ") + error.what());
  }
  if (!root.is_object()) throw InputError(source, 1, "expected a JSON object");
  if (!root.contains("format") || root["format"] != kFormat)
    throw InputError(source, lineOfKey(text, "", "format"), "expected \"format\": \"motionstyle-contacts\"");
  if (!root.contains("version") || !root["version"].is_number_integer() || root["version"].get<int>() != kVersion)
    throw InputError(source, lineOfKey(text, "", "version"), "expected \"version\": 1");
  ContactTracks tracks;
  if (!root.contains("fps") || !root["fps"].is_number() || !(root["fps"].get<double>() > 0.0) ||
      !std::isfinite(root["fps"].get<double>()))
    throw InputError(source, lineOfKey(text, "", "fps"), "expected \"fps\": a positive number");
  tracks.fps = root["fps"].get<double>();
  // The frame count cannot exceed the characters the text holds, so nothing big is allocated for a
  // lying header.
  if (!root.contains("frames") || !root["frames"].is_number_integer() || root["frames"].get<long long>() < 0 ||
      root["frames"].get<long long>() > static_cast<long long>(text.size()))
    throw InputError(source, lineOfKey(text, "", "frames"),
                     "expected \"frames\": a non-negative integer no larger than the tracks");
  const int frames = static_cast<int>(root["frames"].get<long long>());
  readSection(root, "tracks", true, frames, tracks.labels, text, source);
  readSection(root, "overrides", false, frames, tracks.overrides, text, source);
  return tracks;
}

ContactTracks loadContactTracks(const std::filesystem::path& file) {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  if (error) throw InputError(file.string(), 0, "cannot read the contact tracks: " + error.message());
  if (size > kMaxFileBytes) throw InputError(file.string(), 0, "expected a contact file under 256 MiB");
  std::ifstream stream(file, std::ios::binary);
  if (!stream) throw InputError(file.string(), 0, "cannot open the contact tracks for reading");
  std::ostringstream content;
  content << stream.rdbuf();
  if (stream.bad()) throw InputError(file.string(), 0, "cannot read the contact tracks");
  return parseContactTracks(content.str(), file.string());
}

namespace {
std::string formatFps(double fps) {
  std::ostringstream text;
  text << fps;  // 120, 29.97
  return text.str();
}
}  // namespace

Eigen::MatrixXi contactOverridesFromTracks(const ContactTracks& tracks, const ContactLabels& detected, double fps,
                                           const std::filesystem::path& file) {
  if (tracks.labels.rows() != detected.rows() || std::abs(tracks.fps - fps) > 1e-3 * fps)
    throw InputError(file.string(), 0,
                     "holds " + std::to_string(tracks.labels.rows()) + " frames at " + formatFps(tracks.fps) +
                         " fps, the clip " + std::to_string(detected.rows()) + " at " + formatFps(fps));
  Eigen::MatrixXi overrides =
      tracks.overrides.size() > 0 ? tracks.overrides : Eigen::MatrixXi::Constant(tracks.labels.rows(), kContactCount, -1);
  for (Eigen::Index f = 0; f < overrides.rows(); ++f)
    for (Eigen::Index k = 0; k < overrides.cols(); ++k)
      if (overrides(f, k) < 0 && tracks.labels(f, k) != detected(f, k)) overrides(f, k) = tracks.labels(f, k);
  return overrides;
}

}  // namespace motionstyle
