// A run's memory against the process's (run_memory.hpp).
#include "run_memory.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include "drapelab/mujoco/mujoco_mapping.hpp"

namespace drapelab::scene {
namespace {

std::string megabytes(double bytes) {
  return std::to_string(static_cast<long long>(std::ceil(bytes / 1e6))) + " MB";
}

// The scalar at `key` of a solver entry, or `fallback` when absent or not a scalar.
std::string entry_text(const YAML::Node& entry, const char* key, const std::string& fallback) {
  const YAML::Node& constant = entry;  // the non-const operator[] would insert the key
  const YAML::Node value = constant[key];
  return value.IsDefined() && value.IsScalar() ? value.Scalar() : fallback;
}

// Bytes of a kilobyte field of /proc/meminfo ("MemTotal:"), or nothing.
std::optional<double> meminfo_bytes(const std::string& field) {
  std::ifstream meminfo("/proc/meminfo");
  std::string key, unit;
  double kilobytes = 0.0;
  while (meminfo >> key >> kilobytes >> unit)
    if (key == field) return kilobytes * 1024.0;
  return std::nullopt;
}

// The cgroup's memory limit (v2 memory.max, or v1 memory.limit_in_bytes), or nothing when there is
// none ("max", or v1's huge "unlimited" value, above any machine's memory).
std::optional<double> cgroup_limit_bytes() {
  for (const char* file :
       {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    std::ifstream in(file);
    std::string text;
    if (!(in >> text) || text == "max") continue;
    try {
      return std::stod(text);
    } catch (const std::exception&) {
    }
  }
  return std::nullopt;
}

// Bytes in field `index` of /proc/self/statm (0: the whole address space, 5: data and stack).
double statm_bytes(int index) {
  std::ifstream statm("/proc/self/statm");
  double pages = 0.0;
  for (int k = 0; k <= index && (statm >> pages); ++k) {
  }
  return pages * static_cast<double>(sysconf(_SC_PAGESIZE));
}

// What a resource limit leaves (its soft limit less what is in use), or nothing when unlimited.
std::optional<double> rlimit_left(int resource, double in_use) {
  rlimit limit{};
  if (getrlimit(resource, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return std::nullopt;
  return std::max(0.0, static_cast<double>(limit.rlim_cur) - in_use);
}

}  // namespace

std::vector<MemoryPart> run_memory_parts(double particles, const YAML::Node& solvers,
                                         bool self_collision) {
  std::vector<MemoryPart> parts = {
      {"the cloth, its metrics and outputs", kRunBytesPerParticle * particles}};
  if (!solvers.IsSequence()) return parts;
  for (const YAML::Node& entry : solvers) {
    if (!entry.IsMap()) continue;
    const std::string type = entry_text(entry, "type", "spring_damper");
    double per_particle = 0.0;  // B
    if (type == "spring_damper")
      per_particle =
          kSpringDamperBytesPerParticle + (self_collision ? kSelfCollisionBytesPerParticle : 0.0);
    else if (type == "bullet_softbody")
      per_particle = kBulletSoftbodyBytesPerParticle;
    else if (type == "bullet_deformable")
      per_particle = kBulletDeformableBytesPerParticle;
    else if (type == "mujoco")
      per_particle = kMujocoBytesPerParticle;
    else
      continue;
    double bytes = per_particle * particles;
    if (type == "mujoco") {
      const auto dofs = static_cast<std::int64_t>(3.0 * particles);
      // max_contacts when the entry gives a whole number; the solver reader reports any other.
      const std::string given = entry_text(entry, "max_contacts", "0");
      char* end = nullptr;
      const long asked_long = std::strtol(given.c_str(), &end, 10);
      const int asked = *end == '\0' && asked_long > 0 && asked_long < 10000000
                            ? static_cast<int>(asked_long)
                            : 0;
      bytes += mujoco::constraint_buffer_bytes(
          mujoco::contact_capacity(asked, static_cast<std::int64_t>(particles), dofs), dofs);
    }
    const std::string name = entry_text(entry, "name", type);
    parts.push_back({"solver " + name + (name == type ? "" : " (" + type + ")"), bytes});
  }
  return parts;
}

std::optional<MemoryBound> usable_memory() {
  std::optional<MemoryBound> bound;
  const auto tighter = [&](std::optional<double> bytes, const std::string& source) {
    if (bytes && (!bound || *bytes < bound->bytes)) bound = MemoryBound{*bytes, source};
  };
  tighter(meminfo_bytes("MemTotal:"), "the machine's physical memory");
  tighter(cgroup_limit_bytes(), "the cgroup's memory limit");
  tighter(rlimit_left(RLIMIT_AS, statm_bytes(0)), "the address space limit (ulimit -v)");
  tighter(rlimit_left(RLIMIT_DATA, statm_bytes(5)), "the data limit (ulimit -d)");
  return bound;
}

std::optional<std::string> run_memory_problem(double particles,
                                              const std::vector<MemoryPart>& parts,
                                              const MemoryBound& bound) {
  double total = 0.0;  // B
  std::string listed;
  for (const MemoryPart& part : parts) {
    total += part.bytes;
    listed += (listed.empty() ? "" : ", ") + megabytes(part.bytes) + " for " + part.what;
  }
  if (total <= bound.bytes) return std::nullopt;
  return "gives " + std::to_string(static_cast<long long>(particles)) +
         " particles, and a run of them needs about " + megabytes(total) + " of memory (" + listed +
         "), more than the " + megabytes(bound.bytes) + " this process may use (" + bound.source +
         "); use fewer particles or fewer solvers";
}

}  // namespace drapelab::scene
