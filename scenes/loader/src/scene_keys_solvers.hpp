// The keys of each item of `solvers` (solver_reader.cpp). Rows in the order the reader lists valid
// keys: those of every type, then our solver's, then the Bullet cloths' (scene_key.hpp).
#pragma once

#include "scene_key.hpp"
#include "value_ranges.hpp"

namespace drapelab::scene {

inline constexpr SceneKey kSolverKeys[] = {
    {.path = "solvers[].name",
     .type = KeyType::text,
     .given = Given::derived,
     .fallback = "the type",
     .doc = "label in every output, `[a-z0-9_-]+`, 1 to 64 characters (it names "
            "`meshes/NAME.pc2`), unique"},
    {.path = "solvers[].type",
     .type = KeyType::choice,
     .choices = "spring_damper|bullet_softbody|bullet_deformable|mujoco",
     .given = Given::value,
     .fallback = "spring_damper",
     .doc = "`spring_damper` (ours), `bullet_softbody` (Bullet's classic cloth), "
            "`bullet_deformable` (Bullet's deformable world), `mujoco` (MuJoCo 2.2: the cloth's "
            "particles as MuJoCo bodies, [mujoco.md](mujoco.md))"},
    {.path = "solvers[].dt",
     .range = Range::positive(),
     .given = Given::derived,
     .fallback = "automatic",
     .unit = "s",
     .doc = "internal step; must divide the frame period into a whole number of steps, from 1 to "
            "10⁷ per frame (given or automatic). Without `dt` each solver gets the step its "
            "method needs, rounded down to a whole number of steps per frame, and says so in "
            "`summary.json` (`note`); `resolved.yaml` records the value. `spring_damper`: 0.9 × "
            "its integrator's stable-step estimate on its springs, dampers and contact, and on "
            "the self-contact, soft constraints, drags and air that act on single particles "
            "([physics.md](physics.md#the-step-chosen-when-dt-is-left-out): the Gershgorin bound "
            "for symplectic Euler without the contact, whose force it takes at the step's end, "
            "and with it for Verlet and leapfrog, 1.39 × it for RK4, the smallest kd/ks for "
            "explicit Euler and midpoint, or 0.1 × the Gershgorin bound when some spring is "
            "undamped, since they then have no stable step); 1/240 s for `implicit_euler`; 1/120 "
            "s for `vbd` (10 sweeps per step); 1/120 s with `adaptive_substeps` (the solver then "
            "splits each step itself). `bullet_softbody`: the step where ks·w·h² = 0.1 for the "
            "stiffest link, the limit of its stiffness mapping. `bullet_deformable`: 0.9 × the "
            "stable step of its explicit springs. `mujoco`: 0.9 × the stable step of its "
            "explicit springs and contact springs"},
    {.path = "solvers[].round_dt",
     .type = KeyType::boolean,
     .given = Given::value,
     .fallback = "false",
     .doc = "when `true`, a `dt` that does not divide the frame period is rounded down to the "
            "next one that does, and the run says so"},
    {.path = "solvers[].max_speed",
     .range = max_speed_range(),
     .given = Given::derived,
     .fallback = "100 + 2 · \\|g\\| · duration",
     .unit = "m/s",
     .comment = "m/s, runaway limit",
     .doc = "a particle faster than this stops the solver as unstable"},
    {.path = "solvers[].runaway_stretch",
     .range = runaway_stretch_range(),
     .given = Given::value,
     .fallback = "10",
     .comment = "stretch spring strain limit",
     .doc = "a stretch spring longer than (1 + this) × its rest length stops the solver as "
            "unstable (checked every frame)"},
    {.path = "solvers[].integrator",
     .type = KeyType::choice,
     .choices = "explicit_euler|symplectic_euler|midpoint|rk4|verlet|leapfrog|implicit_euler|vbd",
     .when = "spring_damper",
     .given = Given::derived,
     .fallback = "`symplectic_euler`, or `vbd` when chosen",
     .doc = "[physics.md](physics.md#integrators). With neither `integrator` nor `dt`, symplectic "
            "Euler unless its run would take over a minute and four times as long as `vbd`, which "
            "then takes the scene and says so in the `note` "
            "([physics.md](physics.md#the-integrator-chosen-when-none-is-named)); `resolved.yaml` "
            "records the one chosen"},
    {.path = "solvers[].host",
     .type = KeyType::choice,
     .choices = "bullet|none",
     .when = "spring_damper",
     .given = Given::value,
     .fallback = "bullet",
     .comment = "a plugin in a Bullet world, or bare",
     .doc = "`bullet`: our solver is a plugin in a Bullet world, stepped by its pre-tick "
            "callback, with the colliders as kinematic Bullet bodies driven like those of "
            "Bullet's cloths (and dynamic colliders as rigid bodies of that world); `none`: "
            "stepped bare (the results are identical; hosting costs one `stepSimulation` per "
            "step)"},
    {.path = "solvers[].implicit",
     .type = KeyType::map,
     .when = "spring_damper",
     .given = Given::derived,
     .fallback = "see its keys",
     .comment = "conjugate gradient",
     .doc = "`implicit_euler` only (refused with another integrator): the conjugate gradient "
            "stops when the relative residual \\|AΔv − b\\|/\\|b\\| is below `tolerance` or after "
            "`max_iterations`; `summary.json` reports the iterations used and the steps that hit "
            "the cap"},
    {.path = "solvers[].vbd",
     .type = KeyType::map,
     .when = "spring_damper",
     .given = Given::derived,
     .fallback = "see its keys",
     .comment = "sweeps per step",
     .doc = "`vbd` only (refused with another integrator), "
            "[physics.md](physics.md#vertex-block-descent). `summary.json` reports the sweeps, "
            "the colours, the largest move in the last sweep (`vbd_last_sweep_move`, m) and the "
            "contact planes of the last step"},
    {.path = "solvers[].model",
     .type = KeyType::choice,
     .choices = "springs|continuum",
     .when = "spring_damper",
     .given = Given::derived,
     .fallback = "`cloth.model`",
     .doc = "the cloth model this solver runs, whatever the cloth's. A solver with `model: "
            "springs` on a continuum cloth runs the springs derived from it (a preset keeps its "
            "own shear G there); one with `model: continuum` on a springs cloth runs the elements "
            "of `cloth.continuum` (or of the preset, or the defaults). So one scene can run both "
            "models beside Bullet's cloths (`scenes/cusick.yaml`). A springs cloth's "
            "`cloth.continuum` that no solver uses is noted, not refused"},
    {.path = "solvers[].adaptive_substeps",
     .type = KeyType::boolean,
     .when = "spring_damper",
     .given = Given::value,
     .fallback = "false",
     .comment = "split dt into the substeps the shape's stable step needs",
     .doc = "not with `cloth.model: continuum` (an error: the bound is built from the springs). "
            "When `true`, the solver splits every `dt` into as many equal substeps as its cloth's "
            "current shape needs: 0.9 × the stable step of the springs' linearised stiffness at "
            "that shape (each particle's stiffness tensor, "
            "[physics.md](physics.md#adaptive-substeps)), re-evaluated at every `dt`. About 1.4 "
            "to 1.5 times longer steps than the fixed Gershgorin step on a sheet; no gain on a "
            "chain, whose springs at a particle are parallel. `symplectic_euler` only: its damped "
            "stability condition h²ω² + 2hc < 4 is exact, and the bound is tight enough for the "
            "other schemes' differences to matter (Verlet, whose damping lags a step, diverged at "
            "1.4 times its Gershgorin step on a sheet without shear springs). Without `dt`, `dt` "
            "is 1/120 s (every scene in `scenes/` stays stable with one evaluation per 60 Hz "
            "frame). `summary.json` counts the substeps (`integrator_statistics`: `substeps`, "
            "`substeps_per_step_mean`, `_min`, `_max`)"},
    {.path = "solvers[].iterations",
     .type = KeyType::integer,
     .range = {1.0, true, 1000.0, true},
     .when = "bullet_softbody",
     .given = Given::value,
     .fallback = "1",
     .doc = "position-solver sweeps per step"},
    {.path = "solvers[].margin",
     .range = bullet_length_range(),
     .when = "bullet_softbody|bullet_deformable|mujoco",
     .given = Given::derived,
     .fallback = "the cloth's `thickness`",
     .unit = "m",
     .comment = "m, soft collision margin",
     .doc = "the soft body's collision margin: Bullet's cloth rests this far off surfaces; "
            "`mujoco`: the radius of the particles' sphere geoms"},
    {.path = "solvers[].voxel_size",
     .range = bullet_length_range(),
     .when = "bullet_softbody|bullet_deformable",
     .given = Given::derived,
     .fallback = "min(margin, smallest collider feature / 10)",
     .unit = "m",
     .comment = "m, sparse SDF cell",
     .doc = "the cell of Bullet's sparse signed-distance cache (a coarse cell lets nodes sink "
            "into colliders)"},
    {.path = "solvers[].collider_margin",
     .range = bullet_length_range(),
     .when = "bullet_softbody|bullet_deformable",
     .given = Given::value,
     .fallback = "0.001",
     .unit = "m",
     .comment = "m",
     .doc = "the margin Bullet gives boxes and cylinders, which rounds their edges"},
    {.path = "solvers[].kLST",
     .type = KeyType::map,
     .when = "bullet_softbody",
     .fallback = "mapped from ks",
     .doc = "each kind given replaces the mapping kLST = 1 − (1 + ks·w·h²)^(−1/iterations) for "
            "that spring kind"},
    {.path = "solvers[].constraint_solver",
     .type = KeyType::choice,
     .choices = "auto|newton|cg|pgs",
     .when = "mujoco",
     .given = Given::value,
     .fallback = "auto",
     .doc = "MuJoCo's constraint solver; `auto`: Newton up to 3,000 degrees of freedom (1,000 "
            "particles), the conjugate gradient above (MuJoCo 2.2's Newton factors a dense "
            "Hessian)"},
    {.path = "solvers[].solver_iterations",
     .type = KeyType::integer,
     .range = {1.0, true, 10000.0, true},
     .when = "mujoco",
     .given = Given::value,
     .fallback = "100",
     .doc = "the constraint solver's iterations per step at most"},
    {.path = "solvers[].tolerance",
     .range = {0.0, true, 1.0, false},
     .when = "mujoco",
     .given = Given::value,
     .fallback = "1e-10",
     .doc = "the constraint solver stops when its cost improves by less than this, relatively"},
    {.path = "solvers[].impratio",
     .range = {1.0, true, 1e12, true},
     .when = "mujoco",
     .given = Given::derived,
     .fallback = "the ratio at which friction takes out one step's sliding per step",
     .doc = "the friction-to-normal impedance ratio of MuJoCo's elliptic cones. The default, "
            "about m / (c dt) for contact damping c and the mean particle mass m, makes a "
            "contact below the friction angle creep at dt times its tangential acceleration; "
            "1 leaves friction a viscous damper c; much larger makes the friction rows "
            "overshoot and chatter ([mujoco.md](mujoco.md#friction))"},
    {.path = "solvers[].max_contacts",
     .type = KeyType::integer,
     .range = {1.0, true, 1e7, true},
     .when = "mujoco",
     .given = Given::derived,
     .fallback = "one per free particle and 64, within MuJoCo's 2 GB buffer",
     .doc = "the contacts MuJoCo makes room for; a step that needs more stops the solver with an "
            "error (MuJoCo 2.2 would drop them). Its constraint arrays grow as contacts × "
            "degrees of freedom ([mujoco.md](mujoco.md#memory))"},
};

// The maps of a solver: implicit, vbd, kLST.
inline constexpr SceneKey kSolverPartKeys[] = {
    {.path = "solvers[].implicit.tolerance",
     .range = {0.0, false, 1.0, false},
     .given = Given::value,
     .fallback = "1e-6",
     .doc = "the relative residual at which the conjugate gradient stops"},
    {.path = "solvers[].implicit.max_iterations",
     .type = KeyType::integer,
     .range = {1.0, true, 1e6, true},
     .given = Given::value,
     .fallback = "500",
     .doc = "the conjugate gradient's iterations per step at most"},
    {.path = "solvers[].vbd.iterations",
     .type = KeyType::integer,
     .range = {1.0, true, 1e4, true},
     .given = Given::value,
     .fallback = "10",
     .doc = "sweeps per step"},
    {.path = "solvers[].vbd.order",
     .type = KeyType::integer,
     .range = {1.0, true, 2.0, true},
     .given = Given::value,
     .fallback = "1",
     .doc = "1 (backward Euler) or 2 (BDF2)"},
    {.path = "solvers[].vbd.chebyshev_rho",
     .range = {0.0, true, 1.0, false},
     .given = Given::value,
     .fallback = "0",
     .doc = "the Chebyshev acceleration of the sweeps (0: off)"},
    {.path = "solvers[].vbd.friction_velocity",
     .range = {0.0, false, 10.0, true},
     .given = Given::value,
     .fallback = "1e-4",
     .unit = "m/s",
     .doc = "below it a contact sticks"},
    {.path = "solvers[].vbd.coarse",
     .type = KeyType::boolean,
     .given = Given::value,
     .fallback = "true",
     .doc = "the Newton step on the aggregates' translations before every second sweep"},
    {.path = "solvers[].kLST.stretch",
     .range = {0.0, true, 1.0, true},
     .fallback = "mapped",
     .doc = "Bullet's link stiffness of the stretch links"},
    {.path = "solvers[].kLST.shear",
     .range = {0.0, true, 1.0, true},
     .fallback = "mapped",
     .doc = "Bullet's link stiffness of the shear links"},
    {.path = "solvers[].kLST.bend",
     .range = {0.0, true, 1.0, true},
     .fallback = "mapped",
     .doc = "Bullet's link stiffness of the bend links"},
};

}  // namespace drapelab::scene
