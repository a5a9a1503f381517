#pragma once
// The user-editable joint mapping file (JSON), for rigs the automatic mapping cannot read:
//
//   {
//     "format": "motionstyle-joint-mapping",
//     "version": 1,
//     "joints": { "Hips": "pelvis", "LeftHip": "thigh_l", ..., "LeftHandEnd": "hand_l_End" }
//   }
//
// Keys are the 21 canonical names (canonical_joints.h, compared case-insensitively); values are the
// rig's joint names exactly as in its BVH file, End Sites as "<parent>_End". Every canonical joint must
// be given, each hanging below its canonical parent's joint, no rig joint twice. README.md in this folder
// documents it with a full example.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "mapping/joint_mapping.h"

namespace motionstyle {

inline constexpr std::string_view kJointMappingFormat = "motionstyle-joint-mapping";
inline constexpr int kJointMappingVersion = 1;

// Reads a mapping file for `skeleton`. The result's convention is "file:<path>".
// Throws InputError(path, line, ...) for an unreadable file, invalid JSON (line of the error), a wrong
// format or version, an unknown canonical name, a repeated key, a rig joint the skeleton does not have,
// missing canonical joints (all listed) or an inconsistent chain (line 0 when no single line applies).
JointMapping loadJointMapping(const std::filesystem::path& json, const Skeleton& skeleton);

// The same from text in memory; `source_name` names it in errors. Convention: "file:<source_name>".
JointMapping parseJointMapping(std::string_view text, const Skeleton& skeleton, const std::string& source_name);

// The file's text for a complete mapping, canonical joints in feature order.
// Throws std::invalid_argument when the mapping is not valid for the skeleton (describeMappingProblem).
std::string formatJointMapping(const JointMapping& mapping, const Skeleton& skeleton);

// A mapping file to fill in, for a rig the automatic mapping reads only in part: every canonical joint
// with `guess`'s rig joint (guessJointMapping; "" where it found none), above it comments that say what
// to do and list the rig's joints to choose from (the reader ignores comments). Why: writing 21 names
// from a BVH hierarchy by hand is where a user of an unusual rig gives up.
std::string formatJointMappingTemplate(const JointMapping& guess, const Skeleton& skeleton, const std::string& clip_name);

// Writes formatJointMapping atomically (writeFileAtomically): WriteError on failure, nothing changed.
void saveJointMapping(const JointMapping& mapping, const Skeleton& skeleton, const std::filesystem::path& json);

// The mapping file when one is given, else the automatic mapping (which names `source` in its errors).
JointMapping mapJoints(const Skeleton& skeleton, const std::string& source,
                       const std::optional<std::filesystem::path>& mapping_file);

}  // namespace motionstyle
