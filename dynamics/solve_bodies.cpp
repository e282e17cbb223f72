#include "dynamics/solve_bodies.h"

#include <utility>

namespace polysim::dynamics::solver {

SolveBodies::SolveBodies(const std::vector<Row>& rows) {
  // Each world index's number while the rows are numbered, -1 otherwise: kept per thread
  // and cleared again after use, so that numbering costs the rows' size, not the world's
  // (neither a sort nor a fresh array per solve).
  static thread_local std::vector<int> numberOf;
  numbers_.reserve(2 * rows.size());
  for (const Row& r : rows)
    for (const int index : {r.source->a, r.source->b}) {
      if (static_cast<std::size_t>(index) >= numberOf.size()) numberOf.resize(static_cast<std::size_t>(index) + 1, -1);
      int& number = numberOf[static_cast<std::size_t>(index)];
      if (number < 0) number = count_++;
      numbers_.push_back(number);
    }
  for (const Row& r : rows) numberOf[static_cast<std::size_t>(r.source->a)] = numberOf[static_cast<std::size_t>(r.source->b)] = -1;
}

std::vector<RigidBody*> SolveBodies::moving(const std::vector<Row>& rows) const {
  std::vector<RigidBody*> bodies;
  std::vector<char> seen(static_cast<std::size_t>(count_), 0);
  for (std::size_t k = 0; k < rows.size(); ++k)
    for (const auto& [number, body] : {std::pair{a(k), rows[k].a}, std::pair{b(k), rows[k].b}})
      if (char& once = seen[static_cast<std::size_t>(number)]; !body->isStatic && !once) once = 1, bodies.push_back(body);
  return bodies;
}

}  // namespace polysim::dynamics::solver
