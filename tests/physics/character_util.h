#pragma once
// What the character tests share: the box ragdoll's skeleton as a clip, and a box ragdoll (rigid
// unless asked).
#include <string>

#include <glm/gtc/quaternion.hpp>

#include "physics/animation.h"
#include "physics/ragdoll.h"
#include "physics/world.h"

namespace testing_phys {

// The box ragdoll's skeleton (scripts/make-clips writes the same), every hinge at `angle(bone, t)`
// about x, the root still: `frames` frames at 1/60 s.
template <class Angle>
phys::Clip ragdollClip(int frames, Angle angle) {
  phys::Clip c;
  c.name = "test";
  c.bones = {"torso",           "head",           "upper-arm-left", "lower-arm-left",  "upper-arm-right",
             "lower-arm-right", "upper-leg-left", "lower-leg-left", "upper-leg-right", "lower-leg-right"};
  c.parents = {-1, 0, 0, 2, 0, 4, 0, 6, 0, 8};
  c.frameTime = 1.0 / 60.0;
  for (int f = 0; f < frames; ++f) {
    c.root.push_back(phys::Vec3(0.0, 1.17, 0.0));
    for (const std::string& bone : c.bones)
      c.turns.push_back(glm::angleAxis(angle(bone, f * c.frameTime), phys::Vec3(1.0, 0.0, 0.0)));
  }
  return c;
}

inline phys::Ragdoll rigidRagdoll(phys::World& w, const std::string& name,
                                  phys::Vec3 hips = phys::Vec3(0.0, 0.85, 0.0),
                                  phys::RagdollModel model = phys::RagdollModel::Rigid) {
  phys::RagdollDesc d;
  d.name = name;
  d.model = model;
  d.hips = hips;
  return phys::addRagdoll(w, d);
}

}  // namespace testing_phys
