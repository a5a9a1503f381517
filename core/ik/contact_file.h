#pragma once
// Contact tracks saved beside a clip ("clip.bvh.contacts.json"), so that a user's edits survive:
//
//   {
//     "format": "motionstyle-contacts",
//     "version": 1,
//     "fps": 120,
//     "frames": 6,
//     "tracks":    {"LeftHeel": "001110", "LeftToe": "011111", "RightHeel": "110000", "RightToe": "111000"},
//     "overrides": {"LeftHeel": "..11..", "LeftToe": "......", "RightHeel": "0.....", "RightToe": "......"}
//   }
//
// "tracks" (required) holds the effective labels, one character per frame: '1' contact, '0' none.
// "overrides" (optional; any track may be omitted) holds the user's forcing: '.' automatic, '0' forced
// off, '1' forced on. Track names follow ContactLabel order: LeftHeel, LeftToe, RightHeel, RightToe.

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <string_view>

#include "ik/contacts.h"

namespace motionstyle {

struct ContactTracks {
  double fps = 60.0;            // frames per second of the clip the tracks belong to
  ContactLabels labels;         // frames x 4, 0/1
  Eigen::MatrixXi overrides;    // frames x 4, -1 = auto, 0 = off, 1 = on (empty = all automatic)

  // Throws std::invalid_argument on a non-positive fps, labels that are not frames x 4 of 0/1, or
  // overrides that are neither empty nor frames x 4 of -1/0/1.
  void validate() const;
};

// "<clip path>.contacts.json".
std::filesystem::path contactTracksPath(const std::filesystem::path& clip);

std::string formatContactTracks(const ContactTracks& tracks);
// Validates, then writes atomically (WriteError on an I/O failure; the old file stays intact).
void saveContactTracks(const ContactTracks& tracks, const std::filesystem::path& file);

// Throw InputError(file, line, what was expected) on unreadable files, malformed JSON (the parser's
// line), a wrong format or version, a bad fps or frame count, a missing or unknown track, a track of the
// wrong length or with a character outside its alphabet (the line of that track).
ContactTracks parseContactTracks(std::string_view text, const std::string& source_name);
ContactTracks loadContactTracks(const std::filesystem::path& file);

// The clip's overrides (frames x 4, -1/0/1) that `tracks` means against today's detection `detected`
// (frames x 4, 0/1): its overrides, and where a frame has none but its saved label differs from the
// detection, that label, so that a file edited by hand (tracks only) still says what it says. Throws
// InputError naming `file` when the tracks are not of a clip with `detected`'s frames at `fps`.
Eigen::MatrixXi contactOverridesFromTracks(const ContactTracks& tracks, const ContactLabels& detected, double fps,
                                           const std::filesystem::path& file);

}  // namespace motionstyle
