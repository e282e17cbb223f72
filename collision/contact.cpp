#include "collision/contact.h"

#include <algorithm>

namespace polysim::collision {

void Contact::addPoint(const Eigen::Vector3d& x, double gap) {
  if (points.empty()) points.reserve(4), gaps.reserve(4);  // a face's corners at once, not in three growths
  separation = points.empty() ? gap : std::min(separation, gap);
  points.push_back(x);
  gaps.push_back(gap);
}

std::string toString(Status status) {
  switch (status) {
    case Status::Separate: return "separate";
    case Status::Contact: return "contact";
    case Status::Interpenetrating: return "interpenetrating";
  }
  return "?";
}

std::string toString(ContactType type) {
  switch (type) {
    case ContactType::Point: return "point";
    case ContactType::Line: return "line";
    case ContactType::Area: return "area";
  }
  return "?";
}

}  // namespace polysim::collision
