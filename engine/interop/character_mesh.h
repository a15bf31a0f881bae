// A humanoid body of our own for any skeleton with a BodyMap: tapered limbs with elliptical cross-sections,
// a torso following the spine, neck, head, hands and feet, skinned with smooth weights that blend across
// each joint, with normals. Written as assets/character.glb for the built-in skeleton by
// `prep make-character`.
//
// Proportions are fractions of the stature H, which is estimated from the skeleton itself (hip-to-ankle
// height over its anthropometric share of the stature), so the same body fits any humanoid skeleton.
#pragma once

#include <glm/vec3.hpp>

#include "engine/interop/skinned_mesh.h"
#include "engine/motion/body_map.h"
#include "engine/motion/skeleton.h"

namespace prep {

// Anthropometric shape of the body, as fractions of the stature (Drillis & Contini's segment proportions:
// hip joint at 0.530 H, ankle at 0.039 H; girths chosen by us for an average adult).
struct CharacterShape {
  float hip_height = 0.530f;       // hip joint height / stature
  float ankle_height = 0.039f;     // ankle joint height / stature (sole to ankle)
  float thigh_radius[2] = {0.047f, 0.029f};   // at hip, at knee (lateral half-width / H)
  float shin_radius[2] = {0.030f, 0.018f};    // at knee, at ankle
  float upper_arm_radius[2] = {0.028f, 0.021f};
  float forearm_radius[2] = {0.022f, 0.015f};
  float neck_radius = 0.028f;
  float head_half_size[3] = {0.044f, 0.062f, 0.054f};  // lateral, vertical, front-back half-axes / H
  float waist_half_width = 0.078f;
  float torso_depth[5] = {0.058f, 0.066f, 0.058f, 0.070f, 0.040f};  // front-back half-depth at pelvis
                                                                     // bottom, hips, waist, chest, neck base
  float hand_length = 0.108f;
  float hand_half_width = 0.024f;
  float hand_half_thickness = 0.010f;
  float foot_half_width = 0.029f;  // at the ball of the foot
  float blend = 0.25f;             // fraction of a bone's length over which weights blend into the next bone
  int ring_vertices = 16;          // vertices around a limb; the torso and head use 1.5x
};

// The pose the mesh is bound in: the skeleton's rest pose (identity rotations) with the root placed so
// that the soles are on the floor (y = 0).
glm::vec3 character_bind_root(const Skeleton& skeleton, const BodyMap& body, const CharacterShape& shape = {});

// Builds the body. Joint indices and inverse_bind refer to `skeleton`. Throws std::invalid_argument if
// the body map lacks legs or a root.
SkinnedMesh build_character_mesh(const Skeleton& skeleton, const BodyMap& body, const CharacterShape& shape = {});

}  // namespace prep
