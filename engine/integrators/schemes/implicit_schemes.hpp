// The backward Euler schemes: implicit Euler, linearised once per step and solved by conjugate
// gradients (implicit_euler_scheme.cpp), and vbd, the same step minimised by vertex block descent
// (vbd_scheme.cpp). Both take the contacts between particles as couplings of their solves.
#pragma once

#include <memory>

#include "integrators/schemes/scheme.hpp"

namespace drapelab {

class VertexBlockDescent;
class EdgeContact;

// Backward Euler linearised at the step's start (implicit_euler.hpp): the assembled sparse system
// on a cloth without spring families, the matrix-free one on them.
class ImplicitEulerScheme final : public IntegratorScheme {
 public:
  explicit ImplicitEulerScheme(const SchemeContext& context);
  ~ImplicitEulerScheme() override;
  std::optional<std::int64_t> step(double h) override;
  Counters counters() const override;
  std::string step_advice() const override;
  const ImplicitSolveStats* implicit_stats() const override;
  const ImplicitEulerSystem* implicit_system() const override { return assembled_.get(); }
  const FamilyImplicitSystem* family_implicit_system() const override { return matrix_free_.get(); }

 private:
  std::unique_ptr<ImplicitEulerSystem> assembled_;
  std::unique_ptr<FamilyImplicitSystem> matrix_free_;
  Eigen::Matrix3Xd dv_;  // m/s: the step's velocity change
};

// Backward Euler by vertex block descent (vertex_block_descent.hpp).
class VbdScheme final : public IntegratorScheme {
 public:
  explicit VbdScheme(const SchemeContext& context);
  ~VbdScheme() override;
  std::optional<std::int64_t> step(double h) override;
  void finish_step() override;
  Counters counters() const override;
  std::string step_advice() const override;
  const VbdStats* vbd_stats() const override;
  const OffsetContacts* offset_contacts() const override { return self_contacts_.get(); }

 private:
  std::unique_ptr<VertexBlockDescent> descent_;
  std::unique_ptr<EdgeContact> features_;          // the colliders' sharp features; null: none
  std::unique_ptr<OffsetContacts> self_contacts_;  // with self-collision
};

}  // namespace drapelab
