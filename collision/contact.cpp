#include "collision/contact.h"

namespace polysim::collision {

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
