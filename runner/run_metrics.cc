#include "runner/run_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/json_writer.h"

namespace viqu::runner {

double Percentile(std::vector<double> v, double p) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const double pos = p * (v.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(pos));
  const size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - lo) * (v[hi] - v[lo]);
}

double Median(std::vector<double> v) { return Percentile(std::move(v), 0.5); }

std::string MetricsJson(const Scenario& s, const RunMetrics& m) {
  JsonWriter j;
  AddRunMetrics(s, m, &j);
  return j.ToString();
}

void AddRunMetrics(const Scenario& s, const RunMetrics& m, JsonWriter* json) {
  JsonWriter& j = *json;
  j.Set("scenario", s.name);
  j.Set("seed", s.seed);
  j.Set("sim_time_s", m.sim_time_s);
  j.Set("path_length_m", m.path_length_m);
  j.Set("robot.fell", m.fell);
  if (m.fell) j.Set("robot.fell_at_s", m.fell_at_s);
  j.Set("robot.steer_source", m.steer_source);
  j.Set("camera.frames", m.frames);
  j.Set("timing.render_ms_median", Median(m.render_ms));
  j.Set("timing.render_ms_p95", Percentile(m.render_ms, 0.95));
  j.Set("timing.wall_time_s", m.wall_time_s);
  j.Set("timing.real_time_factor", m.wall_time_s > 0 ? m.sim_time_s / m.wall_time_s : 0.0);
  j.Set("timing.renderer", m.renderer);
}

}  // namespace viqu::runner
