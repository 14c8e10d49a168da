#pragma once
// Running statistics of a simulation run, and metrics.json from them.
#include <string>
#include <vector>

#include "common/json_writer.h"
#include "scenario/scenario.h"

namespace viqu::runner {

struct RunMetrics {
  double sim_time_s = 0;              // (s)
  double wall_time_s = 0;             // (s)
  double path_length_m = 0;           // horizontal path of the trunk (m)
  bool fell = false;
  double fell_at_s = 0;       // when the robot first fell (s; with fell)
  std::string fell_how;       // "trunk tilted N deg" | "trunk touched the ground"
  std::vector<double> render_ms;      // per camera frame (ms)
  std::vector<double> track_ms;       // SLAM tracking per camera frame (ms)
  int frames = 0;                     // camera frames produced
  std::string steer_source = "ground_truth";
  std::string renderer;               // EGL device description
};

double Median(std::vector<double> v);
double Percentile(std::vector<double> v, double p);  // p in [0, 1]

// The simulation's metrics.json keys (DESIGN.md), added to `j`.
void AddRunMetrics(const Scenario& s, const RunMetrics& m, JsonWriter* j);
// The metrics.json text of a run without SLAM.
std::string MetricsJson(const Scenario& s, const RunMetrics& m);

}  // namespace viqu::runner
