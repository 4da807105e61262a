// Reading `air:` (see air_reader.hpp).
#include "air_reader.hpp"

#include "value_ranges.hpp"

namespace drapelab::scene {

namespace {

// air.turbulence: {intensity, length}, the eddies carried by the mean wind.
void read_turbulence(SceneReader& reader, MapReader& air_map, AirSettings& air) {
  MapReader map(reader, air_map.get("turbulence"), air_map.path_of("turbulence"),
                {"intensity", "length"});
  if (!map.valid()) return;
  if (!map.has("intensity")) map.missing("intensity", "the eddies' RMS speed in m/s, >= 0");
  if (!map.has("length")) map.missing("length", "the eddies' typical size in m, > 0");
  const auto intensity = map.number("intensity", gust_amplitude_range(), std::nullopt);
  const auto length = map.number("length", turbulence_length_range(), std::nullopt);
  if (!intensity || !length) return;
  air.turbulence_intensity = *intensity;
  air.turbulence_length = *length;
}

}  // namespace

AirSettings read_air(SceneReader& reader, const YAML::Node& node, std::uint64_t seed) {
  AirSettings air;
  MapReader map(reader, node, "air", {"density", "drag", "lift", "wind", "gusts", "turbulence"});
  if (!map.valid()) return air;
  air.enabled = true;
  air.seed = seed;
  air.density = map.number("density", air_density_range(), air.density).value_or(air.density);
  air.drag = map.number("drag", air_coefficient_range(), air.drag).value_or(air.drag);
  air.lift = map.number("lift", air_coefficient_range(), air.lift).value_or(air.lift);
  if (const auto wind = map.numbers("wind", 3, wind_range(), Eigen::Vector3d::Zero()))
    air.wind = *wind;
  if (map.has("turbulence")) read_turbulence(reader, map, air);
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
