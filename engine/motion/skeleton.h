// Sec. 4 data: a joint hierarchy with bone offsets, in metres, Y up.
#pragma once

#include <glm/vec3.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace prep {

struct Joint {
  std::string name;
  int parent = -1;            // index into Skeleton::joints; -1 for the root
  glm::vec3 offset{0.0f};     // translation from the parent joint in the parent's frame (rest pose)
  bool has_end_site = false;  // BVH "End Site": a leaf point such as a toe tip or the top of the head
  glm::vec3 end_site{0.0f};   // its offset from this joint
};

// Joints are stored parents-first (every parent index is smaller than its child's), so forward kinematics
// is one pass in order.
struct Skeleton {
  std::vector<Joint> joints;

  int size() const { return static_cast<int>(joints.size()); }
  int find(std::string_view name) const;  // index of the joint with that name, or -1
  // Throws std::invalid_argument if parents do not precede children or names repeat.
  void validate() const;
};

// The listed joints level by level: by depth below the root, then by index. Parents still come before
// their children, and the joints of one level do not depend on each other, so a kinematics pass in this
// order has several joints' arithmetic in flight at once where skeleton order mostly waits for the
// joint just before (a chain runs parent, child, grandchild). Each joint's arithmetic is the same.
std::vector<int> breadth_first(const Skeleton& skeleton, std::vector<int> joints);

}  // namespace prep
