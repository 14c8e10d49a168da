#include "apps/sweep_spec.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>

#include <yaml-cpp/yaml.h>

#include "common/errors.h"
#include "common/yaml_strict.h"
#include "runner/metric_keys.h"
#include "runner/scenario_settings.h"
#include "scenario/scenario_loader.h"

namespace viqu::app {
namespace {

namespace fs = std::filesystem;

// The most points a sweep may expand to: beyond it a typo in a count is more likely than a plan.
constexpr size_t kMaxPoints = 100000;

// A value as `--set` takes it: scalars as written, lists and maps in YAML flow form.
std::string SetText(const YAML::Node& v) {
  if (v.IsScalar()) return v.Scalar();
  YAML::Emitter out;
  out << YAML::Flow << v;
  return out.c_str();
}

// A map whose keys are free (grid, fixed, best): key nodes and value nodes in file order.
std::vector<std::pair<YAML::Node, YAML::Node>> Entries(const YamlSource& src, const YAML::Node& map, const std::string& key) {
  std::vector<std::pair<YAML::Node, YAML::Node>> out;
  if (!map.IsDefined() || map.IsNull()) return out;
  if (!map.IsMap()) src.Fail(key, map, "key '" + key + "' expected a map, got " + DescribeYamlValue(map));
  std::set<std::string> seen;
  for (const auto& kv : map) {
    const std::string name = kv.first.Scalar();
    if (!seen.insert(name).second) src.Fail(key + "." + name, kv.first, "key '" + key + "." + name + "' appears twice");
    out.emplace_back(kv.first, kv.second);
  }
  return out;
}

}  // namespace

SweepSpec LoadSweepSpec(const std::string& path) {
  SweepSpec spec;
  spec.source_file = path;
  const YamlSource src(path);
  const YAML::Node root = LoadYamlFile(path);
  YamlMapReader top(src, root, "");
  const fs::path base = fs::absolute(path).parent_path();

  top.Require("scenarios");
  const YAML::Node scenarios = top.List("scenarios");
  if (scenarios.size() == 0) src.Fail("scenarios", top.Get("scenarios"), "key 'scenarios' needs at least one scenario file");
  for (size_t i = 0; i < scenarios.size(); ++i) {
    const std::string key = "scenarios." + std::to_string(i);
    const std::string file = ReadYamlString(src, scenarios[i], key);
    const fs::path p = fs::path(file).is_absolute() ? fs::path(file) : base / file;
    std::error_code ec;
    if (!fs::is_regular_file(p, ec)) src.Fail(key, scenarios[i], "scenario file not found: " + p.lexically_normal().string());
    const std::string abs = fs::weakly_canonical(p, ec).string();
    if (std::find(spec.scenarios.begin(), spec.scenarios.end(), abs) != spec.scenarios.end()) {
      src.Fail(key, scenarios[i], "scenario " + abs + " is listed twice");
    }
    spec.scenarios.push_back(abs);
  }

  const YAML::Node seeds = top.Get("seeds");
  if (seeds.IsDefined()) {
    if (seeds.IsScalar()) {
      const int64_t n = ReadYamlInteger(src, seeds, "seeds", NumberRange::Closed(1, 10000));
      for (int64_t s = 1; s <= n; ++s) spec.seeds.push_back(static_cast<uint64_t>(s));
    } else {
      const YAML::Node list = top.List("seeds");
      std::set<uint64_t> seen;
      for (size_t i = 0; i < list.size(); ++i) {
        const uint64_t s = ReadYamlUnsigned(src, list[i], "seeds." + std::to_string(i));
        if (!seen.insert(s).second) src.Fail("seeds." + std::to_string(i), list[i], "seed " + std::to_string(s) + " appears twice");
        spec.seeds.push_back(s);
      }
      if (spec.seeds.empty()) src.Fail("seeds", seeds, "key 'seeds' needs at least one seed (or a count)");
    }
  } else {
    spec.seeds = {1};
  }

  for (const auto& [k, v] : Entries(src, top.Get("grid"), "grid")) {
    const std::string key = k.Scalar();
    if (key == "seed") src.Fail("grid.seed", k, "seeds are swept with the 'seeds' key, not in the grid");
    if (!v.IsSequence() || v.size() == 0) {
      src.Fail("grid." + key, v, "key 'grid." + key + "' expected a non-empty list of values, got " + DescribeYamlValue(v));
    }
    std::vector<std::string> values;
    for (const YAML::Node& x : v) values.push_back(SetText(x));
    spec.grid.emplace_back(key, values);
  }
  for (const auto& [k, v] : Entries(src, top.Get("fixed"), "fixed")) {
    if (k.Scalar() == "seed") src.Fail("fixed.seed", k, "seeds are set with the 'seeds' key");
    for (const auto& [g, values] : spec.grid) {
      if (g == k.Scalar()) src.Fail("fixed." + g, k, "key '" + g + "' is both fixed and in the grid");
    }
    spec.fixed.emplace_back(k.Scalar(), SetText(v));
  }

  const YAML::Node metrics = top.List("metrics");
  // `metrics: []` would run every point and tabulate nothing; leaving the key out gives the defaults.
  if (top.Has("metrics") && metrics.size() == 0) {
    src.Fail("metrics", top.Get("metrics"), "key 'metrics' lists no metric (leave it out for ate.rmse_m and tracking.lost_frames)");
  }
  std::set<std::string> metric_names;
  for (size_t i = 0; i < metrics.size(); ++i) {
    const std::string m = ReadYamlString(src, metrics[i], "metrics." + std::to_string(i));
    if (!metric_names.insert(m).second) src.Fail("metrics." + std::to_string(i), metrics[i], "metric '" + m + "' appears twice");
    if (!runner::IsMetricKey(m)) {
      const std::string nearest = runner::NearestMetricKey(m);
      src.Fail("metrics." + std::to_string(i), metrics[i],
               "'" + m + "' is no metrics.json key (" +
                   (nearest.empty() ? "the keys are listed in DESIGN.md and runner/metric_keys.cc"
                                    : "did you mean '" + nearest + "'?") + ")");
    }
    spec.metrics.push_back(m);
  }
  if (spec.metrics.empty()) spec.metrics = {"ate.rmse_m", "tracking.lost_frames"};
  spec.maximise.assign(spec.metrics.size(), false);
  for (const auto& [k, v] : Entries(src, top.Get("best"), "best")) {
    const std::string m = k.Scalar();
    const auto it = std::find(spec.metrics.begin(), spec.metrics.end(), m);
    if (it == spec.metrics.end()) src.Fail("best." + m, k, "'" + m + "' is not one of the metrics");
    const std::string dir = ReadYamlChoice(src, v, "best." + m, {"min", "max"});
    spec.maximise[static_cast<size_t>(it - spec.metrics.begin())] = dir == "max";
  }
  top.Number("timeout_s", &spec.timeout_s, NumberRange::NonNegative());
  top.RejectUnknownKeys();

  size_t points = spec.scenarios.size() * spec.seeds.size();
  for (const auto& g : spec.grid) {
    points *= g.second.size();
    if (points > kMaxPoints) break;  // before the product can wrap around
  }
  if (points > kMaxPoints) {
    throw InputError(path + ": the sweep expands to more than " + std::to_string(kMaxPoints) + " points");
  }
  // Every point's --set list against its scenario and the SLAM settings it makes: a key or value
  // `viqu run` would reject is reported now, with the point, before anything runs. The loads
  // also give the names.
  spec.scenario_names.assign(spec.scenarios.size(), "");
  std::set<std::string> settings_checked;  // ScenarioSettingsInputs::Key of the points checked
  for (const SweepPoint& p : ExpandSweep(spec)) {
    const size_t s = static_cast<size_t>(std::find(spec.scenarios.begin(), spec.scenarios.end(), p.scenario) -
                                         spec.scenarios.begin());
    try {
      const Scenario scenario = LoadScenario(p.scenario, p.sets);
      // Points that differ only in what the settings do not read (the seed, most often) are
      // checked once.
      const runner::ScenarioSettingsInputs inputs = runner::SettingsInputsOf(scenario);
      if (settings_checked.insert(inputs.Key()).second) runner::LoadScenarioSettings(inputs);
      spec.scenario_names[s] = scenario.name;
    } catch (const InputError& e) {
      throw InputError(path + ": point " + p.id + " (" + p.scenario + "): " + e.what());
    }
  }
  return spec;
}

std::vector<SweepPoint> ExpandSweep(const SweepSpec& spec) {
  std::vector<SweepPoint> out;
  size_t combinations = 1;
  for (const auto& g : spec.grid) combinations *= g.second.size();
  for (size_t s = 0; s < spec.scenarios.size(); ++s) {
    const std::string& scenario = spec.scenarios[s];
    const std::string name = s < spec.scenario_names.size() ? spec.scenario_names[s] : "";
    for (size_t c = 0; c < combinations; ++c) {
      // Combination c, the last grid key fastest.
      std::vector<size_t> index(spec.grid.size());
      size_t rest = c;
      for (size_t g = spec.grid.size(); g-- > 0;) {
        index[g] = rest % spec.grid[g].second.size();
        rest /= spec.grid[g].second.size();
      }
      for (uint64_t seed : spec.seeds) {
        SweepPoint p;
        char id[16];
        std::snprintf(id, sizeof id, "p%04zu", out.size());
        p.id = id;
        p.scenario = scenario;
        p.scenario_name = name;
        p.seed = seed;
        for (const auto& [k, v] : spec.fixed) p.sets.push_back(k + "=" + v);
        for (size_t g = 0; g < spec.grid.size(); ++g) {
          p.values.push_back(spec.grid[g].second[index[g]]);
          p.sets.push_back(spec.grid[g].first + "=" + p.values.back());
        }
        p.sets.push_back("seed=" + std::to_string(seed));
        out.push_back(std::move(p));
      }
    }
  }
  return out;
}

std::string SweepSpecToYaml(const SweepSpec& spec) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "scenarios" << YAML::Value << YAML::BeginSeq;
  for (const std::string& s : spec.scenarios) out << YAML::DoubleQuoted << s;
  out << YAML::EndSeq;
  out << YAML::Key << "seeds" << YAML::Value << YAML::Flow << spec.seeds;
  if (!spec.grid.empty()) {
    out << YAML::Key << "grid" << YAML::Value << YAML::BeginMap;
    for (const auto& [k, values] : spec.grid) {
      out << YAML::Key << k << YAML::Value << YAML::Flow << YAML::BeginSeq;
      for (const std::string& v : values) out << YAML::Load(v);
      out << YAML::EndSeq;
    }
    out << YAML::EndMap;
  }
  if (!spec.fixed.empty()) {
    out << YAML::Key << "fixed" << YAML::Value << YAML::BeginMap;
    for (const auto& [k, v] : spec.fixed) out << YAML::Key << k << YAML::Value << YAML::Load(v);
    out << YAML::EndMap;
  }
  out << YAML::Key << "metrics" << YAML::Value << YAML::Flow << spec.metrics;
  bool any_max = false;
  for (bool m : spec.maximise) any_max = any_max || m;
  if (any_max) {
    out << YAML::Key << "best" << YAML::Value << YAML::BeginMap;
    for (size_t i = 0; i < spec.metrics.size(); ++i) {
      if (spec.maximise[i]) out << YAML::Key << spec.metrics[i] << YAML::Value << "max";
    }
    out << YAML::EndMap;
  }
  if (spec.timeout_s > 0) out << YAML::Key << "timeout_s" << YAML::Value << spec.timeout_s;
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace viqu::app
