// The support polygon: the convex hull, on the floor (x-z plane), of the footprints of the feet in contact.
#pragma once

#include <glm/vec2.hpp>
#include <vector>

#include "engine/motion/contacts.h"

namespace prep {

struct SupportPolygon {
  std::vector<glm::vec2> hull;  // counter-clockwise in (x, z); empty when no foot is in contact (flight)

  bool empty() const { return hull.empty(); }
  bool contains(glm::vec2 p) const;          // inside or on the boundary
  glm::vec2 center() const;                  // area centroid (Eq. 6's p_cos); for a degenerate hull the mean
  float distance_outside(glm::vec2 p) const; // 0 inside, else distance to the hull boundary
};

// A foot in contact contributes a footprint: the heel and/or toe points widened sideways by
// contacts.foot_width (a heel-only or toe-only contact gives a small patch, never a bare line), so that
// single support has an area.
SupportPolygon support_polygon(const FootPoints& feet, const FrameContacts& contacts, const ContactParams& params);
// The same into an existing polygon, reusing its storage (no allocation once its hull has the capacity).
void support_polygon(const FootPoints& feet, const FrameContacts& contacts, const ContactParams& params,
                     SupportPolygon& polygon);

// Convex hull of points (Andrew's monotone chain), counter-clockwise.
std::vector<glm::vec2> convex_hull(std::vector<glm::vec2> points);

}  // namespace prep
