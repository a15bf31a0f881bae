#include "engine/motion/body_map.h"

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <string_view>

#include "engine/motion/joint_names.h"

namespace prep {
namespace {

// A joint name split into its side and its anatomical word, e.g. "mixamorig:LeftUpLeg" -> (left, "upleg"),
// "lShldr" -> (left, "shldr"), "LHipJoint" -> (left, "hipjoint"), "lowerback" -> (none, "lowerback").
struct NamePart {
  int side = -1;  // kLeft, kRight or -1 (on the midline)
  std::string word;
};

using joint_names::lower;

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }
bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

// Words that may follow a one-letter side prefix ("l"/"r"). Checking the word keeps "lowerback" or
// "rootend" from being read as sided.
bool is_limb_word(std::string_view w) {
  static const char* const words[] = {"hipjoint", "buttock", "thigh", "upleg", "upperleg", "hip", "shin", "knee",
                                      "leg", "lowerleg", "calf", "foot", "ankle", "toe", "collar", "clavicle",
                                      "shldr", "shoulder", "arm", "uparm", "upperarm", "forearm", "lowerarm",
                                      "elbow", "hand", "wrist", "finger", "thumb", "index", "mid", "ring", "pinky",
                                      "eye", "heel", "ball"};
  for (const char* word : words)
    if (starts_with(w, word)) return true;
  return false;
}

std::string_view strip_separators(std::string_view s) {
  while (!s.empty() && (s.front() == '_' || s.front() == '.' || s.front() == '-' || s.front() == ' ')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == '_' || s.back() == '.' || s.back() == '-' || s.back() == ' ')) s.remove_suffix(1);
  return s;
}

NamePart split_name(const std::string& name) {
  std::string full = lower(name);
  std::string_view s = full;
  // Namespaces such as Mixamo's "mixamorig:" (also written without the colon).
  if (const size_t colon = s.rfind(':'); colon != std::string_view::npos) s.remove_prefix(colon + 1);
  if (starts_with(s, "mixamorig")) s.remove_prefix(9);
  s = strip_separators(s);
  NamePart part;
  if (starts_with(s, "left")) {
    part.side = kLeft;
    s.remove_prefix(4);
  } else if (starts_with(s, "right")) {
    part.side = kRight;
    s.remove_prefix(5);
  } else if (ends_with(s, "_l") || ends_with(s, ".l")) {
    part.side = kLeft;
    s.remove_suffix(2);
  } else if (ends_with(s, "_r") || ends_with(s, ".r")) {
    part.side = kRight;
    s.remove_suffix(2);
  } else if (s.size() > 1 && (s[0] == 'l' || s[0] == 'r') && is_limb_word(strip_separators(s.substr(1)))) {
    part.side = s[0] == 'l' ? kLeft : kRight;
    s.remove_prefix(1);
  }
  part.word = std::string(strip_separators(s));
  return part;
}

bool is_descendant(const Skeleton& sk, int joint, int ancestor) {
  for (int j = joint; j >= 0; j = sk.joints[static_cast<size_t>(j)].parent)
    if (j == ancestor) return true;
  return false;
}

// The joint of a side whose word scores best (higher score wins, ties go to the joint nearest the root).
template <class Score>
int find_joint(const Skeleton& sk, const std::vector<NamePart>& parts, int side, Score score) {
  int best = -1, best_score = 0;
  for (int j = 0; j < sk.size(); ++j) {
    if (parts[static_cast<size_t>(j)].side != side) continue;
    const int s = score(parts[static_cast<size_t>(j)].word);
    if (s > best_score) {
      best = j;
      best_score = s;
    }
  }
  return best;
}

const char* side_name(int side) { return side == kLeft ? "left" : "right"; }

// Follows first children from `joint` down to the first joint that carries an End Site (the toe tip).
int end_site_below(const Skeleton& sk, int joint) {
  int j = joint;
  while (j >= 0 && !sk.joints[static_cast<size_t>(j)].has_end_site) {
    int child = -1;
    for (int c = j + 1; c < sk.size(); ++c)
      if (sk.joints[static_cast<size_t>(c)].parent == j) {
        child = c;
        break;
      }
    j = child;
  }
  return j;
}

}  // namespace

BodyMap BodyMap::detect(const Skeleton& skeleton) {
  const int n = skeleton.size();
  if (n == 0) throw std::invalid_argument("body map: the skeleton has no joints");
  std::vector<NamePart> parts;
  parts.reserve(static_cast<size_t>(n));
  for (const Joint& j : skeleton.joints) parts.push_back(split_name(j.name));
  const auto parent = [&](int j) { return j < 0 ? -1 : skeleton.joints[static_cast<size_t>(j)].parent; };

  BodyMap body;
  body.root = 0;

  for (int side : {kLeft, kRight}) {
    // Legs are found from the foot up: the ankle ("ankle" in cmu31, else "foot"), its parent the knee, the
    // knee's parent the hip (thigh). Helper bones above the thigh (LHipJoint, lButtock) stay unnamed.
    LegChain& leg = body.legs[static_cast<size_t>(side)];
    leg.ankle = find_joint(skeleton, parts, side, [](const std::string& w) {
      if (starts_with(w, "ankle")) return 2;
      return w == "foot" ? 1 : 0;
    });
    if (leg.ankle < 0) throw std::invalid_argument(std::string("body map: no ") + side_name(side) + " foot/ankle joint");
    leg.knee = parent(leg.ankle);
    leg.hip = parent(leg.knee);
    if (leg.knee <= 0 || leg.hip <= 0)
      throw std::invalid_argument(std::string("body map: the ") + side_name(side) + " foot '" +
                                  skeleton.joints[static_cast<size_t>(leg.ankle)].name + "' has no knee and hip above it");
    for (int c = leg.ankle + 1; c < n; ++c)
      if (parent(c) == leg.ankle && starts_with(parts[static_cast<size_t>(c)].word, "toe")) {
        leg.toe = c;
        break;
      }
    leg.toe_tip_joint = end_site_below(skeleton, leg.toe >= 0 ? leg.toe : leg.ankle);

    // Arms from the hand up: the wrist ("wrist" in cmu31, whose "lhand" is a palm bone below it, else
    // "hand"), elbow, shoulder (upper arm), and the collar if the bone above the upper arm is sided.
    ArmChain& arm = body.arms[static_cast<size_t>(side)];
    arm.wrist = find_joint(skeleton, parts, side, [](const std::string& w) {
      if (starts_with(w, "wrist")) return 2;
      return w == "hand" ? 1 : 0;
    });
    if (arm.wrist < 0) throw std::invalid_argument(std::string("body map: no ") + side_name(side) + " hand/wrist joint");
    arm.elbow = parent(arm.wrist);
    arm.shoulder = parent(arm.elbow);
    if (arm.elbow <= 0 || arm.shoulder <= 0)
      throw std::invalid_argument(std::string("body map: the ") + side_name(side) + " hand '" +
                                  skeleton.joints[static_cast<size_t>(arm.wrist)].name +
                                  "' has no forearm and upper arm above it");
    const int above = parent(arm.shoulder);
    arm.collar = (above > 0 && parts[static_cast<size_t>(above)].side == side) ? above : -1;
  }

  // Head and neck: the neck is the lowest "neck" joint on the way from the root to the head (cmu31 has
  // "lowerneck" below "Neck").
  body.head = find_joint(skeleton, parts, -1, [](const std::string& w) { return starts_with(w, "head") ? 1 : 0; });
  if (body.head < 0) throw std::invalid_argument("body map: no head joint");
  std::vector<int> root_to_head;
  for (int j = body.head; j >= 0; j = parent(j)) root_to_head.push_back(j);
  std::reverse(root_to_head.begin(), root_to_head.end());
  if (root_to_head.front() != body.root) throw std::invalid_argument("body map: the head is not below the root");
  for (int j : root_to_head)
    if (parts[static_cast<size_t>(j)].word.find("neck") != std::string::npos) {
      body.neck = j;
      break;
    }
  const int spine_end = body.neck >= 0 ? body.neck : body.head;
  for (size_t i = 1; i < root_to_head.size() && root_to_head[i] != spine_end; ++i) body.spine.push_back(root_to_head[i]);

  // The upper body is everything hanging from the first spine joint above the pelvis (torso, neck, head,
  // eyes, arms, fingers); the rest is the lower body: the root, the hip helper bones, legs, feet, toes.
  const int upper_root = !body.spine.empty() ? body.spine.front() : spine_end;
  body.upper_body.assign(static_cast<size_t>(n), false);
  body.lower_body.assign(static_cast<size_t>(n), false);
  for (int j = 0; j < n; ++j) {
    bool upper = is_descendant(skeleton, j, upper_root);
    // Arms attached to something other than the spine still belong to the upper body.
    for (const ArmChain& arm : body.arms) upper = upper || is_descendant(skeleton, j, arm.collar >= 0 ? arm.collar : arm.shoulder);
    body.upper_body[static_cast<size_t>(j)] = upper;
    body.lower_body[static_cast<size_t>(j)] = !upper;
  }
  for (const LegChain& leg : body.legs)
    if (body.upper_body[static_cast<size_t>(leg.hip)])
      throw std::invalid_argument("body map: a leg hangs from the spine above the pelvis");
  return body;
}

}  // namespace prep
