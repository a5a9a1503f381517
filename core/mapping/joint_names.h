#pragma once
// Reading a rig's joint names: which side of the body a name says, and what is left once the side and
// the decorations are removed ("mixamorig:LeftUpLeg" -> Left "upleg", "Hand_L" -> Left "hand",
// "lhand" -> Left "hand", "Bip01 L Thigh" -> Left "thigh", "lowerback" -> Centre "lowerback").
//
// A name can often be read several ways ("lhand" is either a centre joint "lhand" or a left "hand"), so
// readJointName returns every plausible reading, most explicit first; the mapper takes the first reading
// that names a joint it knows. Nothing here looks at geometry.

#include <string>
#include <string_view>
#include <vector>

#include "mapping/canonical_joints.h"

namespace motionstyle {

struct JointNameReading {
  BodySide side = BodySide::Center;
  std::string base;  // lower case, no separators, no side marker, e.g. "upleg", "toebase", "spine1"
};

// Readings, in this order:
//  1. an explicit side token: "Left"/"Right"/"L"/"R" split off by a separator (_ - . space) or by
//     camel case ("LeftHip", "LThumb", "Hand_L", "l_hand", "Bip01 L Thigh");
//  2. the whole name as a centre joint;
//  3. a side glued to a lower-case word ("lefthand", "handleft", "lhand", "handl").
// The namespace prefix (anything up to the last ':' or '|') and decoration tokens ("Bip01", "mixamorig",
// "def", "jnt") are dropped first. Returns no readings for a name with nothing left.
std::vector<JointNameReading> readJointName(std::string_view name);

// The name lower-cased with the namespace prefix, separators and decoration tokens removed, side words
// kept: "mixamorig:LeftHandIndex1" -> "lefthandindex1". Used for "contains" tests such as "thumb".
std::string flattenJointName(std::string_view name);

}  // namespace motionstyle
