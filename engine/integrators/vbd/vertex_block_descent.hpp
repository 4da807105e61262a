// The driver of vertex block descent (drapelab/vertex_block_descent.hpp): the particles' spring
// lists and colouring, built once; per step the collider contact planes, the contacts between
// particles, the inertial target y, the initial guess, the sweeps (vbd_loops.hpp) with optional
// Chebyshev acceleration, and the new velocities. Sources: vertex_block_descent.cpp (the step),
// particle_graph.cpp (neighbours, colours, aggregates), coarse_step.cpp (the coarse system).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cstdint>
#include <optional>
#include <vector>

#include "contact/edge_contact.hpp"
#include "drapelab/cloth_model.hpp"
#include "drapelab/contact_model.hpp"
#include "drapelab/vertex_block_descent.hpp"
#include "drapelab/weighted_contact.hpp"
#include "forces/continuum_loops.hpp"
#include "integrators/vbd/vbd_loops.hpp"
#include "self_collision/offset_contacts.hpp"

namespace drapelab {

// Each particle's neighbours: the particles a spring joins it to, and for a continuum cloth those
// sharing a triangle or a hinge with it.
std::vector<std::vector<std::int32_t>> particle_neighbours(const ClothModel& model);

// Greedy colouring of the particles so that no two neighbours share a colour: particles in
// index order, each taking the lowest colour none of its neighbours has. Returns each colour's
// particles in increasing order.
std::vector<std::vector<std::int32_t>> color_particles(const ClothModel& model);

// Aggregates of at most `size` free neighbouring particles, grown breadth first from the
// lowest free particle not yet taken: each particle's aggregate, -1 for a pinned particle.
std::vector<std::int32_t> aggregate_particles(const ClothModel& model, int size);

// Springs per particle as compressed rows (kernels::VbdSprings): particle i's are entries
// offsets[i] to offsets[i + 1] - 1, each spring in both its ends' rows.
struct SpringRows {
  std::vector<std::int32_t> offsets, other;
  std::vector<double> rest_length, ks, kd;  // m, N/m, N*s/m
  kernels::VbdSprings view() const {
    return {offsets.data(), other.data(), rest_length.data(), ks.data(), kd.data()};
  }
};
SpringRows spring_rows(const SpringSet& springs, int particle_count);

// What one step needs besides the state.
struct VbdStepInput {
  double t = 0.0;                                     // s, at the step's start
  double h = 0.0;                                     // s
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  // m/s^2
  double air_damping = 0.0;                           // 1/s
  const ContactModel* contacts = nullptr;             // colliders; none when null
  // Contacts between particles found at the step's start, and the explicit force (N, 3 x N) of
  // the step on each particle besides gravity (their friction); both may be empty.
  const std::vector<WeightedContact>* couplings = nullptr;
  const Eigen::Matrix3Xd* explicit_force = nullptr;
  // Offset self-contacts: detected in the step, every move kept within its conservative bound.
  OffsetContacts* self_contacts = nullptr;
  // The colliders' edges and corners against the cloth's edges and triangles: found at the step's
  // start, measured in the sweeps. Null: none.
  EdgeContact* features = nullptr;
};

class VertexBlockDescent {
 public:
  VertexBlockDescent(const ClothModel& model, VbdSettings settings);

  // One backward Euler step of the cloth from (x, v), both overwritten with the step's end.
  // `totals`, one per collider, receives what each collider's contact did at the end state.
  void step(const ClothModel& model, const VbdStepInput& input, Eigen::Matrix3Xd& x,
            Eigen::Matrix3Xd& v, std::vector<ColliderContactTotals>& totals);

  const VbdSettings& settings() const { return settings_; }
  const VbdStats& stats() const { return stats_; }

 private:
  static constexpr int kPlaneSlots = kernels::kVbdPlaneSlots;

  // Collider contacts for the step: every collider whose surface at the step's end lies within
  // the cloth's thickness plus a margin of a particle's start, as a plane (vbd_loops.hpp).
  // `velocity_step` (s): the step that turns the surface's velocity into its motion in the sweeps.
  void find_planes(const ClothModel& model, const VbdStepInput& input, double velocity_step,
                   const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v);
  // The collider edges and corners near the cloth's edges and triangles for the step, within the
  // same reach as the planes, into the feature arrays.
  void find_features(int n, const VbdStepInput& input, double velocity_step,
                     const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v);
  // How far from a particle's start a collider's surface is taken into the step (m): the
  // thickness plus twice the fastest particle's travel over the step, and at least twice the
  // thickness, so a particle that can reach a surface during the step has it.
  static double contact_reach(const VbdStepInput& input, const Eigen::Matrix3Xd& v);
  // The feature arrays as the sweeps read them, with the contact's thickness (m), stiffness (N/m)
  // and damping (N*s/m).
  kernels::VbdFeatures feature_view(double radius, double stiffness, double damping) const;
  // The per-particle rows of the contacts between particles.
  // `x`: the positions x(n) the contacts were found at.
  // `h` (s): the step, over which a coupling's far end moves by h end_rate.
  void index_couplings(int n, const std::vector<WeightedContact>& couplings,
                       const Eigen::Matrix3Xd& x, double h);
  // A Newton step on G over the aggregates' rigid motions (coarse_step.cpp): the sweeps move each
  // particle against its neighbours, so a motion of a whole region of the cloth against stiff
  // springs (a fall, a skirt swinging or folding off a collider) spreads one colour at a time.
  // `refactor`: factorise the matrix at this iterate (the step's first coarse step); the step's
  // later coarse steps solve their own matrix with that factorisation as a preconditioner.
  void coarse_step(const kernels::VbdProblem& problem, bool refactor, Eigen::Matrix3Xd& x);
  // The coarse matrix's values at the kernel's terms.
  void assemble_coarse_matrix();
  // The coarse step into coarse_move_ by conjugate gradients preconditioned with the last
  // factorisation; false when they do not converge.
  bool solve_with_last_factor();
  void build_coarse_system(const ClothModel& model);
  // Finds the offset self-contacts at the step's start (pins at their end) and keeps the initial
  // guess x within the bounds; returns how many particles it held back.
  std::int64_t detect_self_contacts(const ClothModel& model, OffsetContacts& self,
                                    kernels::VbdProblem& problem, Eigen::Matrix3Xd& x);
  // The cloth's kinetic and stored energy at (x, v) (J): gravity's, the springs' or the
  // continuum's, and what the step's collider planes and features and `self` (may be null) store.
  double mechanical_energy(const kernels::VbdProblem& problem, const Eigen::Vector3d& gravity,
                           const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                           const OffsetContacts* self) const;
  // Whether nothing but the cloth's own forces, gravity and static colliders acts in this step
  // (found planes and features): then backward Euler's step ends with no more energy than it
  // started with. Not for BDF2, whose energy may swing within a step.
  bool passive_step(const ClothModel& model, const VbdStepInput& input) const;
  // How much a passive step may gain (J): far below the energy audit's 1 % of m g L over a run,
  // and above the rounding of `energy`, the start's.
  double energy_slack(const Eigen::Vector3d& gravity, double energy) const;
  // What the collider planes and the couplings against colliders did over the step, at its end
  // state x (h: the step's b, s).
  void record_contact_totals(const Eigen::Matrix3Xd& x, double h,
                             std::vector<ColliderContactTotals>& totals) const;
  void record_feature_totals(const Eigen::Matrix3Xd& x, double h,
                             std::vector<ColliderContactTotals>& totals) const;

  VbdSettings settings_;
  VbdStats stats_;
  // The colliders' penalty contact of the current step.
  struct PlaneContact {
    double radius = 0.0;     // m: the cloth's thickness
    double stiffness = 0.0;  // N/m
    double damping = 0.0;    // N*s/m
  } contact_;
  // Springs per particle and the colouring.
  SpringRows springs_;
  std::vector<std::int32_t> color_offsets_, color_particles_;
  std::vector<std::int32_t> color_of_;  // per particle
  // The coarse step: the aggregates, the pairs of them that springs join, the matrix (its pattern
  // fixed when the solver is built, with the value slots of every block) and its solve. A
  // continuum cloth's springs, which its sweeps do not take, are the coarse step's model of it.
  std::vector<std::int32_t> aggregate_of_, aggregate_offsets_, aggregate_members_;
  std::vector<std::int32_t> pair_aggregates_, pair_offsets_, joining_v0_, joining_v1_;
  std::vector<double> joining_rest_, joining_ks_, joining_kd_;
  SpringRows coarse_springs_;  // a continuum cloth's
  kernels::VbdAggregates aggregates_;
  std::optional<kernels::ContinuumArrays> continuum_;  // cloth.model: continuum
  // Unknowns per aggregate: 6 (a translation and a turn) or 3 (a translation: a large cloth's).
  static constexpr int kRigidUnknowns = 6;
  int coarse_dofs_ = 3;
  std::vector<std::int32_t> diagonal_slots_;  // coarse_dofs_^2 per aggregate
  std::vector<std::int32_t> pair_slots_;      // 2 coarse_dofs_^2 per pair: (a, b), then (b, a)
  // The kernel's terms (kernels::VbdCoarseTerms): per aggregate, mass centre (3), radius, force and
  // torque (6), block (36); per pair, block (36).
  std::vector<double> coarse_centre_, coarse_radius_, coarse_force_, coarse_block_, pair_block_;
  Eigen::VectorXd coarse_rhs_, coarse_move_;  // the aggregates' forces, and the step
  // solve_with_last_factor's vectors, kept so that a step allocates none.
  Eigen::VectorXd cg_residual_, cg_preconditioned_, cg_direction_, cg_product_;
  Eigen::SparseMatrix<double> coarse_matrix_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> coarse_solver_;
  bool coarse_factored_ = false;
  double coarse_reach_ = 0.0;  // m: the longest move of a particle in one coarse step
  // Contact planes, kPlaneSlots per particle.
  std::vector<std::int32_t> plane_count_, plane_collider_;
  std::vector<double> plane_point_, plane_normal_, plane_surface_move_, plane_kinetic_,
      plane_fixed_, plane_load_;
  // Contacts between particles.
  std::vector<std::int32_t> row_scratch_;  // index_contact_rows's
  std::vector<std::int32_t> coupling_offsets_, coupling_contact_, coupling_slot_,
      coupling_particle_;
  std::vector<double> coupling_weight_, coupling_normal_, coupling_depth_, coupling_stiffness_,
      coupling_damping_, coupling_end_rate_;
  // The feature contacts of the current step, as kernels::VbdFeatures reads them.
  std::vector<FeatureContact> near_features_;
  struct FeatureArrays {
    std::vector<std::int32_t> rows, row_contact, row_slot;   // per particle
    std::vector<std::int32_t> particle, range, collider;     // per contact
    std::vector<double> surface_move, kinetic, fixed, load;  // per contact
    std::vector<double> from, to, outward, faces;            // per feature
    void clear() {
      for (auto* list : {&particle, &range, &collider}) list->clear();
      for (auto* list : {&surface_move, &kinetic, &fixed, &load, &from, &to, &outward, &faces})
        list->clear();
    }
  } features_;
  std::vector<std::uint8_t> coupling_two_sided_;
  // Per step (m, 3 x N): the start X (x(n), or BDF2's blend), the inertial target, the sweep's
  // start (read by the contacts between particles), the iteration's start and the one before
  // (Chebyshev's history); V (m/s), the start velocity.
  Eigen::Matrix3Xd start_, inertia_, sweep_start_, iteration_start_, before_last_, base_v_;
  Eigen::Matrix3Xd end_v_;        // m/s: the velocities of the iterate, for its energy
  double weight_height_ = 0.0;    // kg*m: the cloth's mass times its rest extent
  Eigen::Matrix3Xd detection_x_;  // m: where the step's first self-contact detection looks
  // The last step: x(n-1) (m) and v(n-1) (m/s), and its h (s; 0 before the first step).
  Eigen::Matrix3Xd previous_x_, previous_v_;
  double history_step_ = 0.0;
};

}  // namespace drapelab
