// Reading `air:` (see air_reader.hpp).
#include "air_reader.hpp"

#include "value_ranges.hpp"

namespace drapelab::scene {

AirSettings read_air(SceneReader& reader, const YAML::Node& node, std::uint64_t seed) {
  AirSettings air;
  MapReader map(reader, node, "air", {"density", "drag", "lift", "wind", "gusts"});
  if (!map.valid()) return air;
  air.enabled = true;
  air.seed = seed;
  air.density = map.number("density", air_density_range(), air.density).value_or(air.density);
  air.drag = map.number("drag", air_coefficient_range(), air.drag).value_or(air.drag);
  air.lift = map.number("lift", air_coefficient_range(), air.lift).value_or(air.lift);
  if (const auto wind = map.numbers("wind", 3, wind_range(), Eigen::Vector3d::Zero()))
    air.wind = *wind;
  if (!map.has("gusts")) return air;
  MapReader gusts(reader, map.get("gusts"), map.path_of("gusts"), {"amplitude", "period"});
  if (!gusts.valid()) return air;
  if (!gusts.has("amplitude")) gusts.missing("amplitude", "the gusts' RMS speed in m/s, >= 0");
  if (!gusts.has("period")) gusts.missing("period", "the gusts' typical period in s, > 0");
  const auto amplitude = gusts.number("amplitude", gust_amplitude_range(), std::nullopt);
  const auto period = gusts.number("period", gust_period_range(), std::nullopt);
  if (!amplitude || !period) return air;
  if (*amplitude > 0.0 && air.wind.norm() == 0.0) {
    reader.error(map.get("gusts"), map.path_of("gusts"),
                 "vary the wind's speed along its direction, but air.wind is zero; give a wind");
    return air;
  }
  air.gust_amplitude = *amplitude;
  air.gust_period = *period;
  return air;
}

}  // namespace drapelab::scene
