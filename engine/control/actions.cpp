#include "engine/control/actions.h"

#include <stdexcept>

namespace prep {

ActionSpace::ActionSpace(int motions, int alpha_levels, int chosen_levels) : motions_(motions), alpha_levels_(alpha_levels) {
  std::vector<std::vector<int>> all(static_cast<size_t>(motions > 0 ? motions : 0));
  for (auto& list : all)
    for (int m = 0; m < motions; ++m) list.push_back(m);
  build(all, chosen_levels);
}

ActionSpace::ActionSpace(int motions, int alpha_levels, const std::vector<std::vector<int>>& next, int chosen_levels)
    : motions_(motions), alpha_levels_(alpha_levels) {
  build(next, chosen_levels);
}

ActionSpace ActionSpace::from_masks(int motions, int alpha_levels, const std::vector<std::uint64_t>& masks) {
  ActionSpace a(motions, alpha_levels);  // checks the counts
  if (static_cast<int>(masks.size()) != motions) throw std::invalid_argument("actions: one mask per motion is needed");
  const std::uint64_t all = a.size() == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << a.size()) - 1;
  for (int m = 0; m < motions; ++m) {
    const std::uint64_t mask = masks[static_cast<size_t>(m)];
    if (mask == 0 || (mask & ~all) != 0)
      throw std::invalid_argument("actions: the mask of motion " + std::to_string(m) + " is empty or out of range");
    a.masks_[static_cast<size_t>(m)] = mask;
  }
  a.lists_from_masks();
  return a;
}

void ActionSpace::build(const std::vector<std::vector<int>>& next, int chosen_levels) {
  if (motions_ <= 0 || alpha_levels_ <= 0) throw std::invalid_argument("actions: motions and alpha levels must be positive");
  if (size() > 64)
    throw std::invalid_argument("actions: " + std::to_string(size()) + " actions (motions x alpha levels) exceed 64");
  if (static_cast<int>(next.size()) != motions_) throw std::invalid_argument("actions: Next(m) needs one list per motion");
  const int levels = chosen_levels < 0 ? alpha_levels_ : chosen_levels;
  if (levels <= 0 || levels > alpha_levels_) throw std::invalid_argument("actions: chosen levels out of range");
  masks_.assign(static_cast<size_t>(motions_), 0);
  for (int m = 0; m < motions_; ++m) {
    std::uint64_t mask = 0;
    for (int n : next[static_cast<size_t>(m)]) {
      if (n < 0 || n >= motions_) throw std::invalid_argument("actions: Next(m) names a motion out of range");
      for (int l = 0; l < levels; ++l) mask |= std::uint64_t{1} << index({n, l});
    }
    if (mask == 0) throw std::invalid_argument("actions: motion " + std::to_string(m) + " has no successor");
    masks_[static_cast<size_t>(m)] = mask;
  }
  lists_from_masks();
}

void ActionSpace::lists_from_masks() {
  lists_.assign(static_cast<size_t>(motions_), {});
  for (int m = 0; m < motions_; ++m)
    for (int a = 0; a < size(); ++a)
      if (masks_[static_cast<size_t>(m)] >> a & 1u) lists_[static_cast<size_t>(m)].push_back(a);
}

}  // namespace prep
