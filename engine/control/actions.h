// Sec. 6.1, Eq. 12: an action a = {m, alpha}: a core locomotion m, allowed after the last motion by the
// motion graph (Next(m)), played at the preparation level alpha (one of the quantized levels).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/params/params.h"

namespace prep {

struct Action {
  int motion = 0;       // index of the core motion
  int alpha_level = 0;  // level index (alpha = level * alpha_step)
};

// Actions are numbered motion-major: index = motion * alpha_levels + alpha_level. A set of actions is a
// 64-bit mask, so at most 64 actions (e.g. 4 motions x 16 levels); the constructor checks it.
// The alpha levels an action may choose: all of them, or, with QuantizationParams::forced_top_level, all
// but the top one (alpha = 1), which the state then reaches only by the forcing at the source.
inline int action_levels(const QuantizationParams& q) {
  return q.forced_top_level && q.alpha_levels > 1 ? q.alpha_levels - 1 : q.alpha_levels;
}

class ActionSpace {
 public:
  // Every core motion may follow every other (the core nodes of a hierarchical motion graph are
  // connected to each other, Sec. 4.1). Actions are numbered over all alpha_levels (the table and the Q
  // rows keep that layout); only the first `chosen_levels` levels (-1: all) are ever allowed.
  ActionSpace(int motions, int alpha_levels, int chosen_levels = -1);
  // next[m] lists the core motions that may follow m (Next(m) of the motion graph). Each list must be
  // non-empty, else the character could get stuck; throws std::invalid_argument.
  ActionSpace(int motions, int alpha_levels, const std::vector<std::vector<int>>& next, int chosen_levels = -1);
  // The allowed actions given as one mask per last motion (a policy file's); throws std::invalid_argument
  // for an empty mask or one naming actions out of range.
  static ActionSpace from_masks(int motions, int alpha_levels, const std::vector<std::uint64_t>& masks);

  int size() const { return motions_ * alpha_levels_; }
  int motions() const { return motions_; }
  int alpha_levels() const { return alpha_levels_; }
  int index(Action a) const { return a.motion * alpha_levels_ + a.alpha_level; }
  Action decode(int index) const { return {index / alpha_levels_, index % alpha_levels_}; }

  // The actions allowed after last motion m, as a mask and as a list (ascending).
  std::uint64_t allowed_mask(int last_motion) const { return masks_[static_cast<size_t>(last_motion)]; }
  const std::vector<int>& allowed(int last_motion) const { return lists_[static_cast<size_t>(last_motion)]; }

 private:
  void build(const std::vector<std::vector<int>>& next, int chosen_levels);
  void lists_from_masks();
  int motions_, alpha_levels_;
  std::vector<std::uint64_t> masks_;
  std::vector<std::vector<int>> lists_;
};

}  // namespace prep
