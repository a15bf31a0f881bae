#include "engine/motion/skeleton.h"

#include <algorithm>
#include <stdexcept>
#include <unordered_set>

namespace prep {

int Skeleton::find(std::string_view name) const {
  for (int i = 0; i < size(); ++i)
    if (joints[static_cast<size_t>(i)].name == name) return i;
  return -1;
}

void Skeleton::validate() const {
  if (joints.empty()) throw std::invalid_argument("skeleton has no joints");
  if (joints[0].parent != -1) throw std::invalid_argument("joint 0 must be the root");
  std::unordered_set<std::string> names;
  for (int i = 0; i < size(); ++i) {
    const Joint& j = joints[static_cast<size_t>(i)];
    if (i > 0 && (j.parent < 0 || j.parent >= i))
      throw std::invalid_argument("joint '" + j.name + "' does not come after its parent");
    if (!names.insert(j.name).second) throw std::invalid_argument("joint name '" + j.name + "' repeats");
  }
}

std::vector<int> breadth_first(const Skeleton& skeleton, std::vector<int> joints) {
  std::vector<int> depth(skeleton.joints.size(), 0);
  for (size_t j = 0; j < skeleton.joints.size(); ++j) {
    const int parent = skeleton.joints[j].parent;
    if (parent >= 0) depth[j] = depth[static_cast<size_t>(parent)] + 1;
  }
  std::stable_sort(joints.begin(), joints.end(), [&](int a, int b) {
    const int da = depth[static_cast<size_t>(a)], db = depth[static_cast<size_t>(b)];
    return da != db ? da < db : a < b;
  });
  return joints;
}

}  // namespace prep
