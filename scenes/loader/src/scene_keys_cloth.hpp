// The keys of `cloth` and of a pin given as a map, read by cloth_reader.cpp (its fabric's keys:
// scene_keys_fabric.hpp). Rows in the order the reader lists valid keys: the keys of every shape,
// then each shape's own (scene_key.hpp).
#pragma once

#include "scene_key.hpp"
#include "value_ranges.hpp"

namespace drapelab::scene {

inline constexpr SceneKey kClothKeys[] = {
    {.path = "cloth.shape",
     .type = KeyType::choice,
     .choices = "grid|disc|mesh",
     .given = Given::value,
     .fallback = "grid",
     .doc = "`grid`, `disc` (concentric rings, for drape tests) or `mesh` (an OBJ file); each has "
            "its own geometry keys, below, and a key of another shape is an error"},
    {.path = "cloth.center",
     .type = KeyType::numbers,
     .size = 3,
     .range = coordinate_range(),
     .given = Given::derived,
     .fallback = "`[0, 1, 0]`; mesh: `[0, 0, 0]`",
     .unit = "m",
     .comment = "m",
     .doc = "centre of the sheet or disc; a mesh is moved by it (its file coordinates are kept "
            "when left out)"},
    {.path = "cloth.rotation",
     .type = KeyType::numbers,
     .size = 3,
     .range = angle_range(),
     .given = Given::value,
     .fallback = "[0, 0, 0]",
     .unit = "deg",
     .comment = "deg, Euler x, y, z about the centre",
     .doc = "Euler angles (x, y, z) turning the sheet or disc about its centre, or the mesh about "
            "its file origin before `center` (R = Rz·Ry·Rx, as for colliders); for example to lay "
            "a cloth on a tilted board"},
    {.path = "cloth.material",
     .type = KeyType::choice,
     .choices = "silk|cotton|denim|leather",
     .fallback = "none",
     .comment = "a preset; the values below are what it gave, with any explicit keys",
     .doc = "a fabric preset ([materials.md](materials.md)) that sets `areal_density`, "
            "`thickness`, `air_damping` and, with `model: springs`, the three springs, turned into "
            "springs at the cloth's particle spacing (grid: the smaller cell side; disc: radius / "
            "rings; mesh: the mean edge length), or with `model: continuum` the four keys of "
            "`cloth.continuum` ([materials.md](materials.md#with-the-continuum-model)). Any of "
            "those keys given explicitly wins, key by key (`springs: {bend: {ks: 5}}` keeps the "
            "preset's bend kd, `continuum: {poisson: 0.2}` the preset's other three); `mass` "
            "replaces the preset's density"},
    {.path = "cloth.mass",
     .range = mass_range(),
     .given = Given::required,
     .fallback = "required: this or `areal_density`, unless a `material` gives the density",
     .unit = "kg",
     .comment = "kg, total",
     .doc = "in total, split equally among all particles, pinned ones included"},
    {.path = "cloth.areal_density",
     .range = areal_density_range(),
     .fallback = "see `mass`",
     .unit = "kg/m^2",
     .comment = "kg/m^2",
     .doc = "each particle gets density × its vertex area (one third of its incident rest "
            "triangles); not for a chain; not together with `mass`"},
    {.path = "cloth.thickness",
     .range = thickness_range(),
     .given = Given::value,
     .fallback = "0.005",
     .unit = "m",
     .comment = "m",
     .doc = "contact distance kept from colliders"},
    {.path = "cloth.perturbation",
     .range = perturbation_range(),
     .given = Given::value,
     .fallback = "0",
     .unit = "m",
     .comment = "m",
     .doc = "each free particle starts offset along the sheet normal by a uniform random amount "
            "in [−p, p] drawn from `seed` (Mersenne Twister 64, the same on every platform)"},
    {.path = "cloth.model",
     .type = KeyType::choice,
     .choices = "springs|continuum",
     .given = Given::value,
     .fallback = "springs",
     .doc = "`springs`: our solver's cloth is the spring-damper network of `springs`; "
            "`continuum`: a membrane of triangles with hinge bending, given by `continuum` "
            "(below). Every shape takes either; a chain has no triangles, so a grid with one "
            "particle along a side is an error with `continuum`"},
    {.path = "cloth.springs",
     .type = KeyType::map,
     .given = Given::derived,
     .fallback = "see below",
     .comment = "ks in N/m, kd in N*s/m, per spring",
     .doc = "`stretch`, `shear`, `bend`, each `{ks, kd}`; with `model: continuum` an error, since "
            "the springs are then derived from `continuum`"},
    {.path = "cloth.continuum",
     .type = KeyType::map,
     .given = Given::derived,
     .fallback = "see below",
     .doc = "with `model: continuum`, or for the solvers with `model: continuum` (a springs "
            "cloth's block that no solver uses is noted): `stretch_modulus`, `poisson`, "
            "`bending_rigidity`, `damping`"},
    {.path = "cloth.air_damping",
     .range = air_damping_range(),
     .given = Given::value,
     .fallback = "0",
     .unit = "1/s",
     .comment = "1/s",
     .doc = "force −air_damping · m · v on every particle"},
    {.path = "cloth.pins",
     .type = KeyType::list,
     .given = Given::value,
     .fallback = "[]",
     .doc = "list of selectors, below"},
    {.path = "cloth.seams",
     .type = KeyType::list,
     .given = Given::value,
     .fallback = "[]",
     .doc = "seams that sew the cloth's panels together, below; see "
            "[Garments](contact.md#garments-seams)"},
    {.path = "cloth.self_collision",
     .type = KeyType::map,
     .fallback = "off",
     .doc = "the cloth against itself, below"},
    {.path = "cloth.size",
     .type = KeyType::numbers,
     .size = 2,
     .range = cloth_length_range(),
     .when = "grid",
     .given = Given::value,
     .fallback = "[1, 1]",
     .unit = "m",
     .comment = "m",
     .doc = "width along x, depth along the sheet's second axis"},
    {.path = "cloth.resolution",
     .type = KeyType::integers,
     .size = 2,
     .range = resolution_range(),
     .when = "grid",
     .given = Given::required,
     .fallback = "required (grid)",
     .comment = "particles along each side",
     .doc = "`[nx, ny]` particles along each side, at least 2 and at most 1 000 000 particles in "
            "all (a 1000 × 1000 grid: a 2000 × 2000 sheet is an error at this key); `[1, N]` is a "
            "chain (no shear springs, no triangles)"},
    {.path = "cloth.plane",
     .type = KeyType::choice,
     .choices = "xz|xy",
     .when = "grid",
     .given = Given::value,
     .fallback = "xz",
     .doc = "`xz`: horizontal sheet, second axis +z, normal +y; `xy`: vertical sheet, second axis "
            "+y, normal +z"},
    {.path = "cloth.radius",
     .range = cloth_length_range(),
     .when = "disc",
     .given = Given::value,
     .fallback = "0.15",
     .unit = "m",
     .comment = "m",
     .doc = "the disc's radius"},
    {.path = "cloth.rings",
     .type = KeyType::integer,
     .range = rings_range(),
     .when = "disc",
     .given = Given::value,
     .fallback = "20",
     .doc = "rings from the centre to the rim (about π · rings² particles, so about 560 rings "
            "reach the limit); a disc whose rings give more than 1 000 000 particles (many rings, "
            "or a drape support a hair inside the rim, which makes the last ring very narrow and "
            "crowded) is an error stating the count"},
    {.path = "cloth.path",
     .type = KeyType::text,
     .when = "mesh",
     .given = Given::required,
     .fallback = "required (mesh)",
     .doc = "the OBJ file (vertices `v`, faces `f`, optional `vt`; polygons are fanned into "
            "triangles), relative to the scene file; a regular file of at most 64 MB, with at most "
            "1 000 000 vertices and 2 000 000 triangles; a mesh with no area or unusable faces is "
            "an error naming the file and line; a path holding a NUL byte (`\"good.obj\\0x\"`, "
            "which would end the file name early) or another control character is an error"},
    {.path = "cloth.scale",
     .range = mesh_scale_range(),
     .when = "mesh",
     .given = Given::value,
     .fallback = "1",
     .doc = "scales the file's coordinates about the file's origin (before `rotation` and "
            "`center`); the placed mesh must lie within 10⁴ m of the origin along each axis, "
            "measure from 0.001 to 1000 m along its longest side, and keep every triangle's area"},
};

// A pin given as a map: {index: k} or {within: {center, radius}}, either with an `attach`.
inline constexpr SceneKey kPinKeys[] = {
    {.path = "cloth.pins[].index",
     .type = KeyType::integer,
     .range = particle_index_range(),
     .fallback = "none",
     .doc = "a particle index (not with `within`)"},
    {.path = "cloth.pins[].within",
     .type = KeyType::map,
     .fallback = "none",
     .doc = "every particle whose rest position is within `radius` of `center` (not with "
            "`index`)"},
    {.path = "cloth.pins[].attach",
     .type = KeyType::text,
     .fallback = "none",
     .doc = "the name of a collider the pin's particles move with (below)"},
    {.path = "cloth.pins[].within.center",
     .type = KeyType::numbers,
     .size = 3,
     .range = coordinate_range(),
     .given = Given::required,
     .unit = "m",
     .doc = "the ball's centre"},
    {.path = "cloth.pins[].within.radius",
     .range = pin_radius_range(),
     .given = Given::required,
     .unit = "m",
     .doc = "the ball's radius"},
    {.path = "cloth.seams[].a",
     .type = KeyType::list,
     .given = Given::required,
     .doc = "one side of the seam: a list of particle indices, or the name of a grid edge "
            "(`edge_min_x`, ...: its particles in increasing index)"},
    {.path = "cloth.seams[].b",
     .type = KeyType::list,
     .given = Given::required,
     .doc = "the other side, as long as `a`: particle `b[k]` is sewn to `a[k]`"},
    {.path = "cloth.seams[].close_time",
     .range = keyframe_time_range(),
     .given = Given::value,
     .fallback = "0.5",
     .unit = "s",
     .doc = "each stitch's length falls from its rest distance to 0 over this time (0: shut at "
            "once), then stays 0"},
    {.path = "cloth.seams[].stiffness",
     .range = stretch_ks_range(),
     .given = Given::derived,
     .fallback = "the stretch springs' `ks`",
     .unit = "N/m",
     .doc = "each stitch's spring"},
    {.path = "cloth.seams[].damping",
     .range = spring_kd_range(),
     .given = Given::derived,
     .fallback = "the stretch springs' `kd`",
     .unit = "N*s/m",
     .doc = "along each stitch"},
};

}  // namespace drapelab::scene
