// The keys of the cloth's fabric and self-contact: cloth.springs, cloth.continuum and
// cloth.self_collision, read by cloth_reader.cpp, in the order it lists valid keys (scene_key.hpp).
#pragma once

#include "scene_key.hpp"
#include "value_ranges.hpp"

namespace drapelab::scene {

// cloth.springs: three kinds, each {ks, kd}. Stretch springs hold the cloth together, so their ks
// must be > 0; shear and bend may be off.
inline constexpr SceneKey kSpringKeys[] = {
    {.path = "cloth.springs.stretch",
     .type = KeyType::map,
     .given = Given::derived,
     .fallback = "see `ks`, `kd`",
     .doc = "grid neighbours (i±1, j), (i, j±1)"},
    {.path = "cloth.springs.shear",
     .type = KeyType::map,
     .given = Given::derived,
     .fallback = "see `ks`, `kd`",
     .doc = "both diagonals of each cell"},
    {.path = "cloth.springs.bend",
     .type = KeyType::map,
     .given = Given::derived,
     .fallback = "see `ks`, `kd`",
     .doc = "particles two apart along a grid line"},
    {.path = "cloth.springs.stretch.ks",
     .range = stretch_ks_range(),
     .given = Given::value,
     .fallback = "2000",
     .unit = "N/m",
     .doc = "stretch stiffness, per spring"},
    {.path = "cloth.springs.stretch.kd",
     .range = spring_kd_range(),
     .given = Given::value,
     .fallback = "1",
     .unit = "N*s/m",
     .doc = "stretch damping, per spring"},
    {.path = "cloth.springs.shear.ks",
     .range = spring_ks_range(),
     .given = Given::value,
     .fallback = "200",
     .unit = "N/m",
     .doc = "shear stiffness, per spring"},
    {.path = "cloth.springs.shear.kd",
     .range = spring_kd_range(),
     .given = Given::value,
     .fallback = "0.5",
     .unit = "N*s/m",
     .doc = "shear damping, per spring"},
    {.path = "cloth.springs.bend.ks",
     .range = spring_ks_range(),
     .given = Given::value,
     .fallback = "20",
     .unit = "N/m",
     .doc = "bending stiffness, per spring"},
    {.path = "cloth.springs.bend.kd",
     .range = spring_kd_range(),
     .given = Given::value,
     .fallback = "0.1",
     .unit = "N*s/m",
     .doc = "bending damping, per spring"},
};

// cloth.continuum. The comments are those of a continuum cloth; a springs cloth's block for its
// continuum solvers carries the units alone (scene_writer.cpp).
inline constexpr SceneKey kContinuumKeys[] = {
    {.path = "cloth.continuum.stretch_modulus",
     .range = stretch_modulus_range(),
     .given = Given::value,
     .fallback = "300",
     .unit = "N/m",
     .comment = "N/m, Young's modulus x thickness",
     .doc = "Young's modulus × thickness of the membrane"},
    {.path = "cloth.continuum.poisson",
     .range = poisson_range(),
     .given = Given::value,
     .fallback = "0.3",
     .doc = "the in-plane Poisson ratio; the membrane's shear modulus is `stretch_modulus` / (2 "
            "(1 + `poisson`))"},
    {.path = "cloth.continuum.bending_rigidity",
     .range = bending_rigidity_range(),
     .given = Given::value,
     .fallback = "1e-5",
     .unit = "N*m",
     .comment = "N*m",
     .doc = "the fabric's bending rigidity B per unit width (the Kawabata or Peirce B; 1 "
            "gf·cm²/cm = 9.807e-5 N·m)"},
    {.path = "cloth.continuum.damping",
     .range = continuum_damping_range(),
     .given = Given::value,
     .fallback = "0.01",
     .unit = "s",
     .comment = "s, stiffness-proportional",
     .doc = "stiffness-proportional (Kelvin-Voigt) damping of membrane and hinges alike: the "
            "stress of the strain plus `damping` times its rate, so the damping force is "
            "−`damping` × their material stiffness × the velocity, and none for rigid motions"},
};

inline constexpr SceneKey kSelfCollisionKeys[] = {
    {.path = "cloth.self_collision.enabled",
     .type = KeyType::boolean,
     .given = Given::value,
     .fallback = "true",
     .doc = "switch it on or off (off while the map is left out)"},
    {.path = "cloth.self_collision.thickness",
     .range = thickness_range(),
     .given = Given::derived,
     .fallback = "`cloth.thickness`",
     .unit = "m",
     .comment = "m, kept between layers",
     .doc = "the distance two layers keep. It must be below 0.7 of the cloth's shortest rest "
            "edge: a particle lies d/√2 from the far edge of a neighbouring triangle on a square "
            "grid of spacing d, so a thicker layer pushes a flat sheet's neighbouring parts apart "
            "at rest and the run blows up. A thickness at or above it (given here, or taken from "
            "`cloth.thickness`) is an error stating the edge and the bound"},
    {.path = "cloth.self_collision.stiffness",
     .range = contact_stiffness_range(),
     .given = Given::value,
     .fallback = "2000",
     .unit = "N/m",
     .comment = "N/m per contact",
     .doc = "per contact: the penalty spring between layers; it bounds an explicit step like a "
            "spring on the lightest particle"},
    {.path = "cloth.self_collision.damping",
     .range = contact_damping_range(),
     .given = Given::value,
     .fallback = "0.01",
     .unit = "N*s/m",
     .comment = "N*s/m per contact",
     .doc = "per contact: on the closing speed along the contact's normal; it never pulls"},
    {.path = "cloth.self_collision.friction",
     .range = friction_range(),
     .given = Given::value,
     .fallback = "0.3",
     .comment = "kinetic Coulomb coefficient",
     .doc = "kinetic Coulomb coefficient between layers"},
    {.path = "cloth.self_collision.static_friction",
     .range = friction_range(),
     .given = Given::derived,
     .fallback = "`friction`",
     .comment = "static Coulomb coefficient",
     .doc = "static Coulomb coefficient between layers, ≥ `friction`"},
};

}  // namespace drapelab::scene
