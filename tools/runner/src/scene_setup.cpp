#include "drapelab/runner/scene_setup.hpp"

#include "drapelab/grid_cloth.hpp"
#include "drapelab/scene/number_format.hpp"

namespace drapelab::runner {

SceneSetup build_scene_setup(const scene::Scene& scene) {
  SceneSetup setup;
  setup.model = std::make_shared<const ClothModel>(build_grid_cloth(scene.cloth.grid));
  setup.initial =
      initial_grid_state(*setup.model, scene.cloth.grid, scene.cloth.perturbation, scene.seed);
  if (!scene.colliders.empty())
    setup.contacts = std::make_shared<const ContactModel>(
        scene.colliders, ContactParameters{scene.contact.stiffness, scene.contact.damping},
        setup.model->thickness);
  return setup;
}

std::string describe_most_stretched_spring(const ClothModel& model, const ClothState& state) {
  const SpringSet& s = model.springs;
  std::size_t worst = 0;
  double worst_strain = -1.0;
  for (std::size_t e = 0; e < s.size(); ++e) {
    if (s.kind[e] != SpringKind::stretch) continue;
    const double strain =
        (state.x.col(s.v0[e]) - state.x.col(s.v1[e])).norm() / s.rest_length[e] - 1.0;
    if (strain > worst_strain) {
      worst_strain = strain;
      worst = e;
    }
  }
  return "the stretch spring between " + model.describe_particle(s.v0[worst]) + " and " +
         model.describe_particle(s.v1[worst]) + " is stretched by " + format_number(worst_strain);
}

}  // namespace drapelab::runner
