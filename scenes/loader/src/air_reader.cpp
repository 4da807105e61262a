// Reading `air:` (see air_reader.hpp).
#include "air_reader.hpp"

#include "scene_keys.hpp"

namespace drapelab::scene {

namespace {

// air.turbulence: {intensity, length}, the eddies carried by the mean wind.
void read_turbulence(SceneReader& reader, MapReader& air_map, AirSettings& air) {
  MapReader map(reader, air_map.get("turbulence"), air_map.path_of("turbulence"),
                key_names("air.turbulence"));
  if (!map.valid()) return;
  if (!map.has("intensity")) map.missing("intensity", "the eddies' RMS speed in m/s, >= 0");
  if (!map.has("length")) map.missing("length", "the eddies' typical size in m, > 0");
  const auto intensity = map.number(key("air.turbulence.intensity"));
  const auto length = map.number(key("air.turbulence.length"));
  if (!intensity || !length) return;
  air.turbulence_intensity = *intensity;
  air.turbulence_length = *length;
}

}  // namespace

AirSettings read_air(SceneReader& reader, const YAML::Node& node, std::uint64_t seed) {
  AirSettings air;
  MapReader map(reader, node, "air", key_names("air"));
  if (!map.valid()) return air;
  air.enabled = true;
  air.seed = seed;
  air.density = map.number(key("air.density")).value_or(air.density);
  air.drag = map.number(key("air.drag")).value_or(air.drag);
  air.lift = map.number(key("air.lift")).value_or(air.lift);
  if (const auto wind = map.numbers(key("air.wind"))) air.wind = *wind;
  if (map.has("turbulence")) read_turbulence(reader, map, air);
  if (!map.has("gusts")) return air;
  MapReader gusts(reader, map.get("gusts"), map.path_of("gusts"), key_names("air.gusts"));
  if (!gusts.valid()) return air;
  if (!gusts.has("amplitude")) gusts.missing("amplitude", "the gusts' RMS speed in m/s, >= 0");
  if (!gusts.has("period")) gusts.missing("period", "the gusts' typical period in s, > 0");
  const auto amplitude = gusts.number(key("air.gusts.amplitude"));
  const auto period = gusts.number(key("air.gusts.period"));
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
