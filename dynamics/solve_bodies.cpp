#include "dynamics/solve_bodies.h"

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

}  // namespace polysim::dynamics::solver
