#pragma once
// JointMapping: where each of the 21 canonical joints (canonical_joints.h) sits on a user's rig.
//
// The mapping only indexes into the rig's Skeleton, which is kept whole: joints outside the canonical
// set (clavicles, fingers, extra spine or neck joints, twist bones) stay in the skeleton untouched and
// are simply not part of the representation.
//
// mapJoints() finds the joints automatically from the joint names of the common conventions (Bandai
// Namco, CMU/cgspeed, Mixamo, AnimatedDrawings, 3ds Max Biped and similar), using alias lists for the
// limbs and the head and the rig's structure for the rest (README.md in this folder describes the
// rules). Rigs it cannot map need a mapping file (mapping_file.h).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "mapping/canonical_joints.h"
#include "motion/skeleton.h"

namespace motionstyle {

struct JointMapping {
  // joints[index(c)]: index into Skeleton::joints of canonical joint c (End Sites allowed, e.g. a hand
  // end). -1 means "not mapped": a default-constructed mapping, or guessJointMapping()'s gaps.
  std::array<int, kCanonicalJointCount> joints = [] {
    std::array<int, kCanonicalJointCount> none{};
    none.fill(-1);
    return none;
  }();
  // Where the mapping came from: "bandai", "cmu", "mixamo", "animated-drawings", "generic" (found by
  // the automatic rules without a recognised convention) or "file:<path>".
  std::string convention;

  int operator[](CanonicalJoint joint) const { return joints[static_cast<size_t>(index(joint))]; }
  int& operator[](CanonicalJoint joint) { return joints[static_cast<size_t>(index(joint))]; }

  // Canonical joints without a rig joint (-1), in canonical order.
  std::vector<CanonicalJoint> missing() const;
  // missing() as text: "LeftHip, LeftKnee" (empty when every joint is mapped), for messages.
  std::string missingNames() const;

  // Throws std::invalid_argument describing the first problem (describeMappingProblem).
  void validate(const Skeleton& skeleton) const;
};

// The first inconsistency of `mapping` against `skeleton`, or nullopt when it is usable:
// missing canonical joints (all listed), an index out of range, one rig joint used for two canonical
// joints, or a joint that does not hang below its canonical parent's joint (a knee that is not a
// descendant of the hip, an upper arm that is not a descendant of the chest, ...).
std::optional<std::string> describeMappingProblem(const JointMapping& mapping, const Skeleton& skeleton);

// Automatic mapping. Throws InputError(source, 0, ...) when a canonical joint cannot be found; the
// message lists exactly the missing canonical joints in canonical order, says why, and points to the
// mapping file. `source` names the rig's file in messages (may be empty). Reads only joint names and
// rest offsets (file units; used solely to skip zero-length connector joints).
// Throws std::invalid_argument if the skeleton itself is invalid (Skeleton::validate).
JointMapping mapJoints(const Skeleton& skeleton, const std::string& source = "");

// The automatic mapping without throwing: unmapped joints are -1 (e.g. to pre-fill a mapping editor).
JointMapping guessJointMapping(const Skeleton& skeleton);

// The naming convention the rig's joint names follow: "bandai", "cmu", "mixamo", "animated-drawings"
// or "generic".
std::string detectConvention(const Skeleton& skeleton);

}  // namespace motionstyle
