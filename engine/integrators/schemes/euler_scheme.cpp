// The Euler pair: explicit (forward) Euler and symplectic Euler, one force evaluation and one
// per-particle pass per step (integrators/particle_loops.hpp). With colliders each block of
// particles is updated inside the contact phase as soon as its forces are final.
#include "contact/contact_pass.hpp"
#include "forces/spring_families.hpp"
#include "integrators/particle_loops.hpp"
#include "integrators/schemes/euler_schemes.hpp"

namespace drapelab {

std::optional<std::int64_t> EulerScheme::step(double h) {
  const bool symplectic = ctx_.settings.integrator == Integrator::symplectic_euler;
  const double max_speed_squared = ctx_.settings.max_speed * ctx_.settings.max_speed;
  ClothState& state = ctx_.state;
  ForceEvaluator& forces = ctx_.forces;
  const double* inverse_mass = forces.masses().inverse_mass.data();
  if (!forces.has_colliders()) {
    evaluate(state.x, state.v, state.time, h);
    const auto pass = symplectic ? kernels::symplectic_euler_pass : kernels::explicit_euler_pass;
    return pass(ctx_.model.particle_count(), inverse_mass, forces.force().data(), h, state.x.data(),
                state.v.data(), max_speed_squared);
  }
  // With contacts, each block of particles is updated as soon as its contact forces are final, on
  // the thread that computed them and while they are in its cache: the same expressions as the pass
  // above, so the same bits, without a pass (and a start of the threads) of its own. The update's
  // time is then counted in the contact phase. On the spring fast path the block's new state is
  // also split into the kernel's unit-stride arrays there, so the next force evaluation skips its
  // own pass over the state (and a barrier).
  struct EulerUpdate {
    bool symplectic;
    const double* inverse_mass;
    const double* force;
    double h;
    double* x;
    double* v;
    double max_speed_squared;
    SpringFamilies* families;  // null off the fast path
  };
  const EulerUpdate update{
      symplectic,     inverse_mass,   forces.force().data(), h,
      state.x.data(), state.v.data(), max_speed_squared,     forces.spring_families()};
  const ContactBlockFollowUp follow_up{
      [](const void* context, std::int64_t begin, std::int64_t end) {
        const auto& u = *static_cast<const EulerUpdate*>(context);
        const std::int64_t flagged = kernels::euler_range(
            u.symplectic, begin, end, u.inverse_mass, u.force, u.h, u.x, u.v, u.max_speed_squared);
        if (u.families) u.families->split_state(u.x, u.v, begin, end);
        return flagged;
      },
      &update};
  if (forces.spring_families() && !forces.has_pair_terms()) {
    const std::int64_t flagged =
        forces.spring_and_contact_forces_together(state.time, h, follow_up);
    forces.set_split_state_current(true);  // every block was split as it was updated
    return flagged;
  }
  forces.set_body_and_spring_forces(state.x, state.v);
  forces.add_pair_forces(state.x, state.v, state.time, h);
  const std::int64_t flagged =
      forces.add_contact_forces(state.x, state.v, state.time, h, &follow_up);
  forces.set_split_state_current(false);
  return flagged;
}

}  // namespace drapelab
