#include "style/stylize_cleanup_job.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <stdexcept>

#include "features/feature_layout.h"
#include "motion/kinematics.h"
#include "style/cancellation.h"
#include "style/locomotion_kind.h"
#include "style/stylized_cleanup.h"

namespace motionstyle::style {
namespace {

bool sameSkeleton(const Skeleton& a, const Skeleton& b) {
  return std::equal(a.joints.begin(), a.joints.end(), b.joints.begin(), b.joints.end(),
                    [](const Joint& x, const Joint& y) {
                      return x.name == y.name && x.parent == y.parent && x.offset == y.offset &&
                             x.channels == y.channels && x.end_site == y.end_site;
                    });
}

// The same clip, value for value (not its source name: a rename changes no feature).
bool sameContent(const Motion& a, const JointMapping& a_mapping, const Motion& b, const JointMapping& b_mapping) {
  return a.frame_time == b.frame_time && a.values.rows() == b.values.rows() && a.values.cols() == b.values.cols() &&
         a_mapping.joints == b_mapping.joints && a_mapping.convention == b_mapping.convention &&
         sameSkeleton(a.skeleton, b.skeleton) && a.values == b.values;
}

// The content's features: the memory's when they were extracted from this very clip and mapping
// (a live edit changes neither), else extracted now and kept in the memory (or in `own`).
const MotionFeatures& contentFeatures(const Motion& content, const JointMapping& mapping, StylizeCleanupMemory* memory,
                                      std::optional<MotionFeatures>& own) {
  if (!memory) return own.emplace(extractFeatures(content, mapping));
  if (!memory->content_features || !sameContent(content, mapping, memory->content, memory->mapping)) {
    memory->content_features.reset();  // an exception below leaves no stale pairing
    MotionFeatures features = extractFeatures(content, mapping);
    memory->content = content;
    memory->mapping = mapping;
    memory->content_features = std::move(features);
  }
  return *memory->content_features;
}

}  // namespace

void StylizeCleanupJob::validate() const {
  if (!stylized && !stylizer) throw std::invalid_argument("no style network and no stylized clip to clean up");
  if (!(strength >= 0.0 && strength <= 1.0)) throw std::invalid_argument("the strength must be in [0, 1]");
  if (!(output_fps >= 0.0)) throw std::invalid_argument("the output rate must be 0 (the content's) or positive");
  if (contact_overrides.size() > 0 &&
      (contact_overrides.rows() != content.frameCount() || contact_overrides.cols() != kContactCount))
    throw std::invalid_argument("the contact overrides must be content frames x 4");
  requireKindOrNone(kind, "the kind to aim at");
}

void StylizeCleanupMemory::seedFrom(const StylizeCleanupMemory& other) {
  if (&other == this) return;
  cleanup.copySolutionsFrom(other.cleanup);
  content = other.content;
  mapping = other.mapping;
  content_features = other.content_features;
  stylizer = nullptr;
  features.resize(0, 0);
  network_output.resize(0, 0);
}

void StylizeCleanupMemory::copyFrom(const StylizeCleanupMemory& other) {
  if (&other == this) return;
  seedFrom(other);
  stylizer = other.stylizer;
  features = other.features;
  path = other.path;
  kind = other.kind;
  network_output = other.network_output;
}

StylizeCleanupResult StylizeCleanupJob::run(const std::atomic<bool>* cancel) const {
  validate();
  if (memory && seed && !memory->content_features && !memory->stylizer) memory->seedFrom(*seed);
  const auto start = std::chrono::steady_clock::now();
  StylizeCleanupResult result;
  std::optional<MotionFeatures> own_features;  // the features when there is no memory to keep them
  if (stylized) {
    result.stylized = *stylized;
  } else {
    const MotionFeatures& features = contentFeatures(content, mapping, memory.get(), own_features);
    throwIfCancelled(cancel);
    if (!memory) {
      result.stylized = stylizer->stylize(features, strength, path, kind);
    } else {
      result.network_output_kept = memory->stylizer == stylizer && memory->path == path && memory->kind == kind &&
                                   memory->features.rows() == features.values.rows() &&
                                   memory->features.cols() == features.values.cols() &&
                                   memory->features == features.values;
      if (!result.network_output_kept) {
        memory->stylizer = nullptr;  // an exception below leaves no stale pairing
        memory->network_output = stylizer->networkOutput(features.values, features.contacts, path, kind, cancel);
        memory->features = features.values;
        memory->path = path;
        memory->kind = kind;
        memory->stylizer = stylizer;
      }
      result.stylized = stylizer->stylize(features, memory->network_output, strength, path, kind);
    }
  }
  throwIfCancelled(cancel);
  StylizedCleanup cleanup = cleanUpStylizedClip(content, mapping, result.stylized, options, output_fps, contact_overrides,
                                                CleanupControl{cancel, memory ? &memory->cleanup : nullptr});
  throwIfCancelled(cancel);
  result.cleaned = std::move(cleanup.motion);
  if (world_positions) result.cleaned_world_positions = worldPositions(result.cleaned);
  result.report = std::move(cleanup.report);
  result.raw_metrics = std::move(cleanup.raw);
  result.cleaned_metrics = std::move(cleanup.cleaned);
  result.contacts = std::move(cleanup.contacts);
  result.cleanup_fps = cleanup.fps;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace motionstyle::style
