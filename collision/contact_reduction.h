#pragma once
// The polygon tests see one polygon pair at a time, so a box on a triangulated floor
// yields one area piece per triangle, and every edge and vertex on that area again as
// lines and points. Reduction turns these into the contacts a user expects: each
// coplanar set of area pieces merged into one polygon, collinear line pieces joined,
// and lines and points dropped when they lie on a reported area or line.

#include <vector>

#include "collision/contact.h"

namespace polysim::collision {

/// The contacts of one object pair with every contact reported once. `eps` (m) is the
/// contact tolerance: pieces within eps of each other are the same contact.
std::vector<Contact> reduceContacts(const std::vector<Contact>& raw, double eps);

}  // namespace polysim::collision
