#include "dataset/manifest.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "map/map_json.hpp"
#include "surrogate/features.hpp"

namespace plumekit::dataset {

std::string shard_name(int map_index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "shard-%05d", map_index);
  return buf;
}

namespace {

// The flow cell the maps are solved with: flow.cell, or the default resolved
// on the maps (cfd::resolved_cell), which is 0.05 m on every map up to
// building scale, so that such datasets record what they always did; "auto"
// only where maps of different sizes resolve differently.
nlohmann::ordered_json flow_cell_json(const DatasetOptions& o) {
  if (o.flow.cell != 0.0) return o.flow.cell;
  if (o.given_maps.empty()) return cfd::resolved_cell(o.map.width, o.map.height, o.flow);
  const double first = cfd::resolved_cell(o.given_maps.front(), o.flow);
  for (const Map& m : o.given_maps)
    if (cfd::resolved_cell(m, o.flow) != first) return "auto";
  return first;
}

}  // namespace

double drawn_inlet_speed(const DatasetOptions& o, int index, int redraw) {
  // Its own stream (not the geometry's), so the maps' shapes are those of the same seed without it.
  std::mt19937_64 rng(
      derive_seed(o.seed, index, static_cast<std::uint64_t>(redraw), Stream::InletSpeed));
  const double unit = static_cast<double>(rng() >> 11) * 0x1.0p-53;
  const double u =
      std::round((o.inlet_speed_lo + (o.inlet_speed_hi - o.inlet_speed_lo) * unit) * 100.0) / 100.0;
  return std::clamp(u, o.inlet_speed_lo, o.inlet_speed_hi);  // bounds that are not whole cm/s
}

nlohmann::ordered_json parameters_json(const DatasetOptions& o) {
  const world::FilamentOptions& f = o.plume.filament;
  const cfd::AdvectionDiffusionOptions& a = o.plume.advection_diffusion;
  nlohmann::ordered_json j;
  j["seed"] = o.seed;
  j["seeding"] =
      "every random stream is SplitMix64-derived from (seed, map index, source index, purpose): "
      "map geometry, sources, filament walk";
  j["maps"] = o.given_maps.empty() ? o.maps : static_cast<int>(o.given_maps.size());
  if (o.given_maps.empty()) {
    j["sources_per_map"] = o.sources;
    j["source_clearance_m"] = o.source_clearance;
    j["random_maps"] = {{"width", o.map.width},
                        {"height", o.map.height},
                        {"inlet_speed", o.map.inlet_speed},
                        {"end_clearance", o.map.end_clearance},
                        {"robot_margin", o.map.robot_margin},
                        {"min_gap", o.map.min_gap}};
    // Only when not the thesis's four, so that older manifests still match on resume.
    if (o.map.families != RandomMapOptions::thesis_families())
      j["random_maps"]["families"] = o.map.families;
  } else {
    j["map_files"] = o.map_files;
    j["sources_per_map"] = "each map's own sources";
  }
  // The v2 grid and drawn inlet speeds, only when used, so that older manifests match on resume.
  if (o.feature_cell > 0) j["feature_cell"] = o.feature_cell;
  if (o.physics_input) {
    const cfd::AdvectionDiffusionOptions p = physics_mean_options(o);
    j["physics_input"] = true;
    j["physics_mean"] = {{"diffusivity", p.diffusivity},
                         {"decay_rate", p.decay_rate},
                         {"release_rate", p.release_rate}};
  }
  if (o.inlet_speed_hi > 0) j["inlet_speeds"] = {o.inlet_speed_lo, o.inlet_speed_hi};
  j["flow"] = {{"cell", flow_cell_json(o)},
               {"nu", o.flow.nu},
               {"turbulence", cfd::to_string(o.flow.turbulence)},
               {"convection", cfd::to_string(o.flow.convection)},
               {"tolerance", o.flow.tolerance}};
  j["plume_model"] = to_string(o.plume.model);
  if (o.plume.model == PlumeSimulator::Filament) {
    j["filament"] = {{"release_per_second", f.release_per_second},
                     {"release_rate", f.release_rate},
                     {"initial_radius", f.initial_radius},
                     {"growth", f.growth},
                     {"sigma_walk", f.sigma_walk},
                     {"meander_speed", f.meander_speed},
                     {"meander_time", f.meander_time},
                     {"dt", f.dt},
                     {"max_radius", f.max_radius},
                     {"steady_window", f.steady_window},
                     {"steady_tolerance", f.steady_tolerance},
                     {"min_spinup", f.min_spinup},
                     {"max_spinup", f.max_spinup},
                     {"record_s", f.record_s},
                     {"sample_rate", f.sample_rate},
                     {"cutoff", f.cutoff},
                     {"equivalent_diffusivity", f.equivalent_diffusivity()}};
    // Only when on, so that manifests written before the option still match on resume.
    if (f.occlusion) j["filament"]["occlusion"] = true;
    // The fast engine only (issue 45): a dataset made before it is V1's, and resumes only with
    // --world ...-v1, never mixed with the other engine's plumes.
    if (f.engine == world::PlumeEngine::Fast) j["filament"]["engine"] = "fast";
    if (f.source_radius > 0.0) j["filament"]["source_radius"] = f.source_radius;
    if (f.unsteady_wind) {
      j["filament"]["wind_model"] = "unsteady";
      j["filament"]["meander_length"] = f.meander_length;
      j["filament"]["meander_wall_layer"] = f.meander_wall_layer;
    }
  } else {
    j["advection_diffusion"] = {{"diffusivity", a.diffusivity},
                                {"release_rate", a.release_rate},
                                {"scheme", "finite volumes on the flow grid, Patankar hybrid"}};
  }
  // Only when not the ideal sensor at 0, so that manifests written before the option still match.
  const world::GasSensorModel& g = o.plume.sensor;
  if (!g.ideal() || g.baseline != 0.0)
    j["sensor"] = {{"gas", g.name},
                   {"baseline", g.baseline},
                   {"rise_s", g.rise_s},
                   {"rise_slow_s", g.rise_slow_s},
                   {"fast_share", g.fast_share},
                   {"decay_s", g.decay_s},
                   {"dead_rise_s", g.dead_rise_s},
                   {"dead_decay_s", g.dead_decay_s},
                   {"warmup_s", world::sensor_warmup_s(g)}};
  return j;
}

cfd::AdvectionDiffusionOptions physics_mean_options(const DatasetOptions& o) {
  cfd::AdvectionDiffusionOptions p = o.plume.advection_diffusion;
  p.decay_rate = 1.0 / o.plume.filament.lifetime_s();
  return p;
}

nlohmann::ordered_json contract_json(double feature_cell, bool physics_input) {
  nlohmann::ordered_json j;
  const bool physical = feature_cell > 0;
  const std::string order =
      "C order, [..., row j, column i]; row 0 at y = 0 (bottom), column 0 at x = 0 (left): flip "
      "rows to show with y up";
  if (physical) {
    j["grid"] = {{"cell", feature_cell},
                 {"nx", "max(1, round(W / cell)), per map"},
                 {"ny", "max(1, round(H / cell)), per map"},
                 {"extent",
                  "the whole map, cell-centred: centre (i + 0.5) * W / nx, (j + 0.5) * H / ny; "
                  "each shard (one map) has its own nx, ny"},
                 {"order", order}};
  } else {
    j["grid"] = {{"nx", 64},
                 {"ny", 64},
                 {"extent",
                  "the whole arena, cell-centred: centre (i + 0.5) * W / 64, "
                  "(j + 0.5) * H / 64"},
                 {"order", order}};
  }
  nlohmann::ordered_json channels = {
      "0: region label of the cell centre as a float: inside obstacle 0, free 1, wall 2, "
      "inlet 3, outlet 4 (plumekit's rasterization rule: centre inside or on an obstacle "
      "boundary is obstacle; free cells on the arena edge take their wall's label)",
      "1: signed distance in metres from the cell centre to the nearest solid surface "
      "(obstacle edges and the arena walls outside the inlet and outlet), computed exactly "
      "from the polygons; negative inside obstacles"};
  if (physical) {
    channels.push_back(
        "2: the map's steady wind (wind/map-NNNNN/), u in m/s at the cell centre, bilinear "
        "between the flow's cell centres, 0 in the flow's solid cells");
    channels.push_back("3: the same wind's v in m/s");
    if (physics_input)
      channels.push_back(
          "4: physics_mean: the steady advection-diffusion concentration of the source's release "
          "in the same wind (generator.physics_mean: diffusivity, decay_rate, release_rate), on "
          "the flow grid, bilinear among free flow cells at the cell centre, 0 inside obstacles; "
          "target units, no sensor baseline");
    channels.push_back(std::to_string(physics_input ? 5 : 4) +
                       ": Euclidean distance in metres from the cell centre to the source (not "
                       "its inverse)");
  } else {
    channels.push_back(
        "2: Euclidean distance in metres from the cell centre to the source (not its inverse)");
  }
  const int count = surrogate::input_channels(feature_cell, physics_input);
  j["inputs"] = {{"dtype", "float32"},
                 {"shape", physical ? "[n, " + std::to_string(count) + ", ny, nx]"
                                    : std::string("[n, 3, 64, 64]")},
                 {"names", surrogate::input_channel_names(feature_cell, physics_input)},
                 {"channels", channels}};
  j["targets"] = {
      {"dtype", "float32"},
      {"shape", physical ? "[n, 2, ny, nx]" : "[n, 2, 64, 64]"},
      {"channels",
       {"0: mean concentration at the sensor (the cell centre)",
        "1: standard deviation of the concentration over the recording (population std; "
        "0 everywhere for the advection-diffusion model)"}},
      {"units",
       "concentration units of a release of release_rate per metre of depth "
       "(units * m^2/s); with the default 1000 values run 0..~3000, like the thesis's "
       "unnormalised dataset; sensors inside obstacles read 0"}};
  j["sources"] = {{"dtype", "float32"}, {"shape", "[n, 2]"}, {"meaning", "x, y in metres"}};
  j["map_ids"] = {{"dtype", "int32"},
                  {"shape", "[n]"},
                  {"meaning", "index of the map: maps/map-NNNNN.json, wind/map-NNNNN/"}};
  return j;
}

nlohmann::ordered_json manifest_json(const nlohmann::ordered_json& parameters,
                                     const std::vector<ShardEntry>& shards, int part_k,
                                     int part_n) {
  nlohmann::ordered_json j;
  j["format"] = kDatasetFormat;
  if (part_n > 1) j["part"] = {{"k", part_k}, {"n", part_n}};
  j["generator"] = parameters;
  j["contract"] = contract_json(parameters.value("feature_cell", 0.0),
                                parameters.value("physics_input", false));
  long long samples = 0;
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const ShardEntry& s : shards) {
    samples += s.samples;
    nlohmann::ordered_json sums = nlohmann::ordered_json::object();
    for (const auto& [name, hex] : s.checksums)
      sums[name] = hex;
    list.push_back({{"name", shard_name(s.map_index)},
                    {"map_index", s.map_index},
                    {"map", "maps/map-" + shard_name(s.map_index).substr(6) + ".json"},
                    {"family", s.family},
                    {"samples", s.samples},
                    {"sha256", sums}});
  }
  j["samples"] = samples;
  j["checksum"] = "SHA-256 of each file (as sha256sum prints it)";
  j["shards"] = list;
  return j;
}

}  // namespace plumekit::dataset
