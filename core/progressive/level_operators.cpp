#include "progressive/level_operators.hpp"

#include <string>

#include "common/error.hpp"
#include "hierarchy/level_prolongation.hpp"

namespace progsim {

LevelOperators::LevelOperators(std::shared_ptr<const MeshHierarchy> hierarchy)
    : hierarchy_(std::move(hierarchy)),
      next_(hierarchy_->num_levels()),
      direct_(hierarchy_->num_levels()) {}

const std::shared_ptr<const ShellProlongation>& LevelOperators::next(int level) const {
  if (!next_.at(level))
    next_[level] =
        std::make_shared<const ShellProlongation>(next_level_prolongation(*hierarchy_, level));
  return next_[level];
}

std::vector<std::shared_ptr<const ShellProlongation>> LevelOperators::to_finest(
    int level, ProxyProlongation prolongation) const {
  const int finest = hierarchy_->finest();
  if (level < 0 || level >= finest)
    fail(Status::out_of_range, "levels [0, " + std::to_string(finest) +
                                   ") prolong to the finest level, not level " +
                                   std::to_string(level));
  if (prolongation == ProxyProlongation::direct) {
    if (!direct_[level])
      direct_[level] =
          std::make_shared<const ShellProlongation>(direct_prolongation(*hierarchy_, level));
    return {direct_[level]};
  }
  std::vector<std::shared_ptr<const ShellProlongation>> chain;
  for (int k = level; k < finest; ++k) chain.push_back(next(k));
  return chain;
}

}  // namespace progsim
