// Implicit Euler as a scheme: one force evaluation at the step's start, its linear solve for dv,
// then v(n+1) = v(n) + dv, x(n+1) = x(n) + h v(n+1).
#include <sstream>

#include "integrators/family_implicit.hpp"
#include "integrators/schemes/implicit_schemes.hpp"

namespace drapelab {

ImplicitEulerScheme::ImplicitEulerScheme(const SchemeContext& context) : IntegratorScheme(context) {
  if (ctx_.forces.spring_families())
    matrix_free_ = std::make_unique<FamilyImplicitSystem>(
        ctx_.model, *ctx_.forces.spring_families(), ctx_.settings.implicit);
  else
    assembled_ = std::make_unique<ImplicitEulerSystem>(ctx_.model, ctx_.settings.implicit);
  dv_.resize(3, ctx_.model.particle_count());
}

ImplicitEulerScheme::~ImplicitEulerScheme() = default;

std::optional<std::int64_t> ImplicitEulerScheme::step(double h) {
  ClothState& state = ctx_.state;
  ForceEvaluator& forces = ctx_.forces;
  evaluate(state.x, state.v, state.time, h);
  const ContactParameters contact =
      ctx_.settings.contacts ? ctx_.settings.contacts->parameters() : ContactParameters{};
  if (matrix_free_)
    matrix_free_->solve(ctx_.model, state.x, state.v, forces.force(), h, ctx_.settings.air_damping,
                        contact, forces.active_contacts(), forces.couplings(), dv_);
  else
    assembled_->solve(ctx_.model, state.x, state.v, forces.force(), h, ctx_.settings.air_damping,
                      contact, forces.active_contacts(), forces.couplings(), dv_);
  state.v += dv_;                    // v(n+1) = v(n) + dv
  state.x.noalias() += h * state.v;  // x(n+1) = x(n) + h v(n+1)
  return std::nullopt;
}

const ImplicitSolveStats* ImplicitEulerScheme::implicit_stats() const {
  return matrix_free_ ? &matrix_free_->stats() : &assembled_->stats();
}

Counters ImplicitEulerScheme::counters() const {
  const ImplicitSolveStats& cg = *implicit_stats();
  const double mean =
      cg.solves > 0 ? static_cast<double>(cg.iterations_total) / static_cast<double>(cg.solves)
                    : 0.0;
  return {{"cg_solves", static_cast<double>(cg.solves)},
          {"cg_iterations_total", static_cast<double>(cg.iterations_total)},
          {"cg_iterations_mean", mean},
          {"cg_iterations_max", cg.iterations_max},
          {"cg_relative_residual_max", cg.residual_max},
          {"cg_unconverged_steps", static_cast<double>(cg.unconverged)},
          {"cg_tolerance", ctx_.settings.implicit.tolerance},
          {"cg_max_iterations", ctx_.settings.implicit.max_iterations}};
}

std::string ImplicitEulerScheme::step_advice() const {
  std::ostringstream text;
  text.precision(4);
  text << "a smaller dt or a larger implicit max_iterations (the conjugate gradient reached a "
          "relative "
          "residual of "
       << implicit_stats()->residual_last << " in " << implicit_stats()->iterations_last
       << " iterations; a collider moving faster than its contact can push back also needs a "
          "smaller dt), ";
  return text.str();
}

}  // namespace drapelab
