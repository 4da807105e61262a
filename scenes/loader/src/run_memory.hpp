// A run's memory, estimated from the cloth's particle count and the solvers' types before anything
// is built, against the memory this process may use: a run the machine cannot hold is refused at
// the key that sizes the cloth in a second, not with "out of memory" after minutes and gigabytes.
#pragma once

#include <yaml-cpp/yaml.h>

#include <optional>
#include <string>
#include <vector>

namespace drapelab::scene {

// Bytes per particle of each part of a run, measured as the peak resident memory of one-frame runs
// of 200 x 200 to 400 x 400 grids (the differences between sizes; every shape has about six
// springs and two triangles per particle): the cloth, its initial state, the metrics and the
// outputs, shared by the solvers; then each solver's own state.
inline constexpr double kRunBytesPerParticle = 1600.0;
inline constexpr double kSpringDamperBytesPerParticle = 1400.0;   // the implicit solve's or vbd's
inline constexpr double kSelfCollisionBytesPerParticle = 1300.0;  // our solver's self-contact
inline constexpr double kBulletSoftbodyBytesPerParticle = 2300.0;
inline constexpr double kBulletDeformableBytesPerParticle = 2800.0;
// MuJoCo's model and data without its constraint arrays, which grow as contacts x degrees of
// freedom and are added from mujoco::constraint_buffer_bytes.
inline constexpr double kMujocoBytesPerParticle = 3000.0;

// One part of the estimate, for the message.
struct MemoryPart {
  std::string what;    // "the cloth and its metrics", "solver ours (bullet_softbody)"
  double bytes = 0.0;  // B
};

// The run's parts for `particles` particles and the solvers of the scene's `solvers` list (items
// that are not solvers are skipped: the loader reports them). `self_collision`: the cloth has it on
// (our solver's contacts take memory).
std::vector<MemoryPart> run_memory_parts(double particles, const YAML::Node& solvers,
                                         bool self_collision);

// The memory this process may take (B) and where the bound comes from: the machine's physical
// memory (MemTotal), or less where the process is held to less: a cgroup's memory.max, an address
// space limit (ulimit -v, less what the process maps already) or a data limit (ulimit -d).
struct MemoryBound {
  double bytes = 0.0;
  std::string source;  // "physical memory", "ulimit -v", ...
};
std::optional<MemoryBound> usable_memory();

// Why a run of these parts, for `particles` particles, does not fit in `bound`, or nothing: "gives
// 1000000 particles, and a run of them needs about 7300 MB (...), more than the 3000 MB this
// process may use (the address space limit (ulimit -v)); ...".
std::optional<std::string> run_memory_problem(double particles,
                                              const std::vector<MemoryPart>& parts,
                                              const MemoryBound& bound);

}  // namespace drapelab::scene
