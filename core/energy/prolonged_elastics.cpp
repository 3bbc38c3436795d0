#include "energy/prolonged_elastics.hpp"

#include "common/error.hpp"

namespace progsim {

ProlongedElastics::ProlongedElastics(std::shared_ptr<const ShellProlongation> to_finest,
                                     std::vector<std::unique_ptr<EnergyTerm>> finest_terms,
                                     std::vector<std::unique_ptr<EnergyTerm>> level_terms)
    : ProlongedElastics(std::vector<std::shared_ptr<const ShellProlongation>>{std::move(to_finest)},
                        std::move(finest_terms), std::move(level_terms)) {}

ProlongedElastics::ProlongedElastics(std::vector<std::shared_ptr<const ShellProlongation>> chain,
                                     std::vector<std::unique_ptr<EnergyTerm>> finest_terms,
                                     std::vector<std::unique_ptr<EnergyTerm>> level_terms)
    : chain_(std::move(chain)), level_terms_(std::move(level_terms)) {
  if (chain_.empty()) fail(Status::invalid_argument, "prolonged elastics: no prolongation");
  for (std::size_t k = 0; k < chain_.size(); ++k) {
    if (!chain_[k]) fail(Status::invalid_argument, "prolonged elastics: a null prolongation");
    if (k > 0 && chain_[k]->coarse_vertices() != chain_[k - 1]->fine_vertices())
      fail(Status::invalid_argument, "prolonged elastics: the chain's levels do not connect");
    states_.emplace_back(chain_[k]->coarse_vertices(), 3);
    gradients_.emplace_back(chain_[k]->coarse_vertices(), 3);
  }
  workspaces_.resize(chain_.size());
  const int n_fine = chain_.back()->fine_vertices();
  gradients_.emplace_back(n_fine, 3);
  finest_ = std::make_unique<Problem>(3 * n_fine);
  for (auto& term : finest_terms) finest_->add_term(std::move(term));
  entry_offsets_.push_back(0);
  for (const auto& term : level_terms_)
    entry_offsets_.push_back(entry_offsets_.back() + term->hessian_entry_count());
  fine_.setZero(n_fine, 3);
  fine_dofs_.resize(3 * n_fine);
  fine_gradient_dofs_.resize(3 * n_fine);
}

ProlongedElastics::ProlongedElastics(std::vector<std::shared_ptr<const ShellProlongation>> chain,
                                     std::vector<std::unique_ptr<EnergyTerm>> finest_terms,
                                     const Positions& finest_rest, double refresh_distance)
    : ProlongedElastics(std::move(chain), std::move(finest_terms),
                        std::vector<std::unique_ptr<EnergyTerm>>{}) {
  ProlongationMatrix intrinsic = chain_.front()->intrinsic();  // U = U_L^{L−1} ⋯ U_{l+1}^l
  for (std::size_t k = 1; k < chain_.size(); ++k)
    intrinsic = ProlongationMatrix(chain_[k]->intrinsic() * intrinsic);
  finest_->finalize();
  galerkin_ = std::make_unique<GalerkinHessian>(intrinsic, *finest_, as_dofs(finest_rest),
                                                refresh_distance);
}

std::size_t ProlongedElastics::hessian_entry_count() const {
  return galerkin_ ? galerkin_->entry_count() : entry_offsets_.back();
}

void ProlongedElastics::prolong(const Vector& x) const {
  if (x.size() != states_[0].size())
    fail(Status::invalid_argument, "prolonged elastics: x has " + std::to_string(x.size()) +
                                       " DOFs, the level has " + std::to_string(states_[0].size()));
  states_[0] = as_positions(x);  // same size: no allocation
  for (std::size_t k = 0; k < chain_.size(); ++k)
    chain_[k]->apply(states_[k], k + 1 < chain_.size() ? states_[k + 1] : fine_);
  for (std::size_t k = 0; k < pinned_.size(); ++k)
    fine_(pinned_[k] / 3, pinned_[k] % 3) = pinned_values_[k];
  fine_dofs_ = as_dofs(fine_);
}

void ProlongedElastics::pin_finest_dofs(const std::vector<int>& dofs, const Vector& values) {
  if (values.size() != static_cast<Eigen::Index>(dofs.size()))
    fail(Status::invalid_argument, "prolonged elastics: " + std::to_string(dofs.size()) +
                                       " pinned DOFs but " + std::to_string(values.size()) +
                                       " values");
  for (int d : dofs)
    if (d < 0 || d >= fine_.size())
      fail(Status::out_of_range,
           "prolonged elastics: pinned DOF " + std::to_string(d) + " is not a finest DOF");
  pinned_ = dofs;
  pinned_values_ = values;
}

double ProlongedElastics::value(const Vector& x) const {
  prolong(x);
  return finest_->value(fine_dofs_);  // Ψ_L(P^l(x)), PSQ eq. 2
}

void ProlongedElastics::add_gradient(const Vector& x, Vector& g) const {
  prolong(x);
  finest_->gradient(fine_dofs_, fine_gradient_dofs_);
  gradients_.back() = as_positions(fine_gradient_dofs_);
  for (int d : pinned_) gradients_.back()(d / 3, d % 3) = 0.0;  // held: independent of x
  // ∇_x Ψ_L(P(x)) = J(x)ᵀ ∇Ψ_L, the exact chain rule through each operator (PSQ eqs. 7, 9).
  for (std::size_t k = chain_.size(); k-- > 0;) {
    gradients_[k].setZero();
    chain_[k]->add_jacobian_transpose(states_[k], gradients_[k + 1], gradients_[k], workspaces_[k]);
  }
  g += as_dofs(gradients_[0]);
}

void ProlongedElastics::hessian_pattern(int* rows, int* cols) const {
  if (galerkin_) return galerkin_->pattern(rows, cols);
  for (std::size_t k = 0; k < level_terms_.size(); ++k)
    level_terms_[k]->hessian_pattern(rows + entry_offsets_[k], cols + entry_offsets_[k]);
}

void ProlongedElastics::hessian_values(const Vector& x, bool project_psd, double* values) const {
  if (galerkin_) {
    prolong(x);
    return galerkin_->values(fine_dofs_, project_psd, pinned_, values);
  }
  // ∇²Ψ_l(x_l): the level's own shell Hessian (PSQ Algorithm 1 line 7).
  for (std::size_t k = 0; k < level_terms_.size(); ++k)
    level_terms_[k]->hessian_values(x, project_psd, values + entry_offsets_[k]);
}

void ProlongedElastics::refresh_hessian() {
  if (galerkin_) galerkin_->refresh();
}

std::vector<TermStats> ProlongedElastics::finest_term_stats() const {
  std::vector<TermStats> stats = finest_->term_stats();
  for (TermStats& s : stats) s.name += "@finest";
  return stats;
}

}  // namespace progsim
