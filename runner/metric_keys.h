#pragma once
// The single-valued keys a run's metrics.json can hold (`viqu run`, and `viqu slam` on a dataset), dotted as in
// DESIGN.md ("ate.rmse_m" is {"ate": {"rmse_m": ...}}): the names a sweep's `metrics:` may ask
// for. Which of them a given run writes depends on its mode (lo.*, slip.* in `full`; dynamic.* with
// the dynamic stage; dataset and camera keys in replays). test_scenario_slam_replay checks that
// every key a live run, its replay and a EuRoC replay write is listed here.
#include <string>
#include <vector>

namespace viqu::runner {

// Every key, sorted.
const std::vector<std::string>& MetricKeys();
bool IsMetricKey(const std::string& key);
// The listed key nearest to `key` (fewest single-character edits), for an error message; "" when
// none is within a third of the key's length.
std::string NearestMetricKey(const std::string& key);

}  // namespace viqu::runner
