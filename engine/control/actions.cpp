#include "engine/control/actions.h"

#include <stdexcept>

namespace prep {

ActionSpace::ActionSpace(int motions, int alpha_levels) : motions_(motions), alpha_levels_(alpha_levels) {
  std::vector<std::vector<int>> all(static_cast<size_t>(motions > 0 ? motions : 0));
  for (auto& list : all)
    for (int m = 0; m < motions; ++m) list.push_back(m);
  build(all);
}

ActionSpace::ActionSpace(int motions, int alpha_levels, const std::vector<std::vector<int>>& next)
    : motions_(motions), alpha_levels_(alpha_levels) {
  build(next);
}

void ActionSpace::build(const std::vector<std::vector<int>>& next) {
  if (motions_ <= 0 || alpha_levels_ <= 0) throw std::invalid_argument("actions: motions and alpha levels must be positive");
  if (size() > 64)
    throw std::invalid_argument("actions: " + std::to_string(size()) + " actions (motions x alpha levels) exceed 64");
  if (static_cast<int>(next.size()) != motions_) throw std::invalid_argument("actions: Next(m) needs one list per motion");
  masks_.assign(static_cast<size_t>(motions_), 0);
  lists_.assign(static_cast<size_t>(motions_), {});
  for (int m = 0; m < motions_; ++m) {
    std::uint64_t mask = 0;
    for (int n : next[static_cast<size_t>(m)]) {
      if (n < 0 || n >= motions_) throw std::invalid_argument("actions: Next(m) names a motion out of range");
      for (int l = 0; l < alpha_levels_; ++l) mask |= std::uint64_t{1} << index({n, l});
    }
    if (mask == 0) throw std::invalid_argument("actions: motion " + std::to_string(m) + " has no successor");
    masks_[static_cast<size_t>(m)] = mask;
    for (int a = 0; a < size(); ++a)
      if (mask >> a & 1u) lists_[static_cast<size_t>(m)].push_back(a);
  }
}

}  // namespace prep
