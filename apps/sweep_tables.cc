#include "apps/sweep_tables.h"


#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>

#include <yaml-cpp/yaml.h>

#include "common/atomic_file.h"
#include "common/run_folder.h"
#include "common/yaml_strict.h"

namespace viqu::app {
namespace {

namespace fs = std::filesystem;

// The value at a dotted key of a JSON object read as YAML; "" when absent or not a scalar.
std::string Lookup(const YAML::Node& root, const std::string& dotted) {
  // yaml-cpp: `node = other` would assign into the node; reset() rebinds it.
  YAML::Node node;
  node.reset(root);
  size_t start = 0;
  while (true) {
    const size_t dot = dotted.find('.', start);
    const std::string key = dotted.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (!node.IsMap() || !node[key]) return "";
    node.reset(node[key]);
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return node.IsScalar() && node.Scalar() != "null" ? node.Scalar() : "";
}

bool ParseNumber(const std::string& text, double* x) {
  if (text.empty()) return false;
  if (text == "true" || text == "false") {
    *x = text == "true" ? 1 : 0;
    return true;
  }
  char* end = nullptr;
  *x = std::strtod(text.c_str(), &end);
  return end != text.c_str() && *end == '\0' && std::isfinite(*x);
}

std::string Number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", x);
  return buf;
}

}  // namespace

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

PointOutcome ReadPointOutcome(const SweepSpec& spec, const std::string& run_dir) {
  PointOutcome o;
  o.metrics.assign(spec.metrics.size(), "");
  std::error_code ec;
  if (!fs::exists(run_dir, ec) || !IsCompleteRunFolder(run_dir)) {
    o.status = "missing";
    return o;
  }
  try {
    const YAML::Node marker = LoadRunJsonFile(run_dir + "/" + kRunCompleteMarker);
    o.exit_code = marker["exit_code"] ? marker["exit_code"].Scalar() : "";
    const YAML::Node metrics = LoadRunJsonFile(run_dir + "/metrics.json");
    for (size_t i = 0; i < spec.metrics.size(); ++i) o.metrics[i] = Lookup(metrics, spec.metrics[i]);
    o.wall_s = Lookup(metrics, "timing.wall_time_s");
  } catch (const std::exception&) {
    o.status = "missing";
    return o;
  }
  o.status = o.exit_code == "0" ? "ok" : "failed";
  return o;
}

std::vector<std::string> WriteSweepTables(const SweepSpec& spec, const std::vector<SweepPoint>& points,
                                          const std::vector<PointOutcome>& outcomes, const std::string& dir) {
  std::string header = "id,scenario,seed";
  for (const auto& g : spec.grid) header += "," + CsvField(g.first);
  std::string results = header;
  for (const std::string& m : spec.metrics) results += "," + CsvField(m);
  results += ",exit_code,status,wall_s\n";

  // Grid points (scenario and grid values) in first-seen order, with their points.
  // Grouped by scenario file (two files may share a name) and grid values.
  std::vector<std::string> group_keys;
  std::map<std::string, std::vector<size_t>> groups;
  for (size_t i = 0; i < points.size(); ++i) {
    const SweepPoint& p = points[i];
    const PointOutcome& o = outcomes[i];
    std::string row = p.id + "," + CsvField(p.scenario_name) + "," + std::to_string(p.seed);
    std::string key = CsvField(p.scenario_name);
    for (const std::string& v : p.values) {
      row += "," + CsvField(v);
      key += "," + CsvField(v);
    }
    key = p.scenario + "\n" + key;  // the file first; the part after the newline is printed
    for (const std::string& m : o.metrics) row += "," + CsvField(m);
    row += "," + o.exit_code + "," + o.status + "," + o.wall_s + "\n";
    results += row;
    if (!groups.count(key)) group_keys.push_back(key);
    groups[key].push_back(i);
  }

  std::string summary = "scenario";
  for (const auto& g : spec.grid) summary += "," + CsvField(g.first);
  summary += ",points,ok";
  for (const std::string& m : spec.metrics) {
    for (const char* stat : {"mean", "std", "min", "max", "n"}) summary += "," + CsvField(m + "." + stat);
  }
  summary += "\n";
  std::vector<std::string> best_lines(spec.metrics.size());
  std::vector<double> best(spec.metrics.size(), NAN);
  for (const std::string& key : group_keys) {
    const std::vector<size_t>& members = groups[key];
    int ok = 0;
    for (size_t i : members) ok += outcomes[i].status == "ok" ? 1 : 0;
    summary += key.substr(key.find('\n') + 1) + "," + std::to_string(members.size()) + "," + std::to_string(ok);
    for (size_t m = 0; m < spec.metrics.size(); ++m) {
      std::vector<double> xs;
      // Only runs that ended well count: a robot that fell early has a short, flattering trajectory.
      for (size_t i : members) {
        double x;
        if (outcomes[i].status == "ok" && ParseNumber(outcomes[i].metrics[m], &x)) xs.push_back(x);
      }
      if (xs.empty()) {
        summary += ",,,,,0";
        continue;
      }
      double sum = 0, lo = xs[0], hi = xs[0];
      for (double x : xs) {
        sum += x;
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
      const double mean = sum / xs.size();
      double var = 0;
      for (double x : xs) var += (x - mean) * (x - mean);
      // Sample std over seeds; with one value there is none (blank, not 0).
      const std::string sd = xs.size() > 1 ? Number(std::sqrt(var / (xs.size() - 1))) : "";
      summary += "," + Number(mean) + "," + sd + "," + Number(lo) + "," + Number(hi) + "," + std::to_string(xs.size());
      const bool better = std::isnan(best[m]) || (spec.maximise[m] ? mean > best[m] : mean < best[m]);
      if (better) {
        best[m] = mean;
        std::string where = points[members.front()].scenario_name;
        for (size_t g = 0; g < spec.grid.size(); ++g) where += ", " + spec.grid[g].first + "=" + points[members.front()].values[g];
        best_lines[m] = spec.metrics[m] + " (" + (spec.maximise[m] ? "max" : "min") + "): " + Number(mean) + " mean over " +
                        std::to_string(xs.size()) + " seed(s) at " + where;
      }
    }
    summary += "\n";
  }
  WriteFileAtomic(dir + "/results.csv", results);
  WriteFileAtomic(dir + "/summary.csv", summary);
  std::vector<std::string> lines;
  for (size_t m = 0; m < spec.metrics.size(); ++m) {
    lines.push_back(best_lines[m].empty() ? spec.metrics[m] + ": no values" : best_lines[m]);
  }
  return lines;
}

}  // namespace viqu::app
