// Sweep files (apps/sweep_spec.h) and sweep tables (apps/sweep_tables.h) without running the
// simulator: strict parsing with file:line:col, the grid expansion, the resolved copy, and the
// tables built from run folders made here with known metrics.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "apps/sweep_spec.h"
#include "apps/sweep_tables.h"
#include "common/errors.h"
#include "common/run_folder.h"

namespace viqu::app {
namespace {

namespace fs = std::filesystem;

const std::string kScenario = std::string(VIQU_SOURCE_DIR) + "/scenarios/static_room.yaml";

class SweepTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("viqu_sweep_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  std::string Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  std::string ErrorOf(const std::string& text) {
    const std::string path = Write("bad.yaml", text);
    try {
      LoadSweepSpec(path);
    } catch (const InputError& e) {
      return e.what();
    }
    return "<no InputError>";
  }
  fs::path dir_;
};

TEST_F(SweepTest, ExpandsScenariosTimesGridTimesSeedsLastKeyFastest) {
  const std::string path = Write("s.yaml", "scenarios: [" + kScenario + "]\nseeds: 2\ngrid:\n"
                                           "  sensors.camera.noise_std: [1, 4]\n  robot.start.xy: [[0, 0], [0.5, 0.5], [1, 1]]\n"
                                           "fixed: {duration_s: 2}\nmetrics: [ate.rmse_m, dynamic.recall]\nbest: {dynamic.recall: max}\n");
  const SweepSpec spec = LoadSweepSpec(path);
  EXPECT_EQ(spec.seeds, (std::vector<uint64_t>{1, 2}));
  EXPECT_EQ(spec.maximise, (std::vector<bool>{false, true}));
  const std::vector<SweepPoint> points = ExpandSweep(spec);
  ASSERT_EQ(points.size(), 12u);  // 1 scenario x 2 x 3 x 2 seeds
  EXPECT_EQ(points[0].id, "p0000");
  EXPECT_EQ(points[11].id, "p0011");
  EXPECT_EQ(points[0].scenario_name, "static_room");
  // Seeds fastest, then the last grid key, then the first.
  EXPECT_EQ(points[1].seed, 2u);
  EXPECT_EQ(points[1].values, (std::vector<std::string>{"1", "[0, 0]"}));
  EXPECT_EQ(points[2].values, (std::vector<std::string>{"1", "[0.5, 0.5]"}));
  EXPECT_EQ(points[6].values, (std::vector<std::string>{"4", "[0, 0]"}));
  EXPECT_EQ(points[3].sets, (std::vector<std::string>{"duration_s=2", "sensors.camera.noise_std=1",
                                                      "robot.start.xy=[0.5, 0.5]", "seed=2"}));
  // The resolved copy expands to the same points.
  const SweepSpec again = LoadSweepSpec(Write("resolved.yaml", SweepSpecToYaml(spec)));
  const std::vector<SweepPoint> points2 = ExpandSweep(again);
  ASSERT_EQ(points2.size(), points.size());
  for (size_t i = 0; i < points.size(); ++i) EXPECT_EQ(points2[i].sets, points[i].sets) << i;
  EXPECT_EQ(again.maximise, spec.maximise);
}

TEST_F(SweepTest, BadSweepFilesNameFileLineAndColumn) {
  const std::string s = "scenarios: [" + kScenario + "]\n";
  EXPECT_NE(ErrorOf(s + "seed: [1]\n").find("bad.yaml:2:1: unknown key 'seed' (expected one of: scenarios, seeds, grid"),
            std::string::npos)
      << ErrorOf(s + "seed: [1]\n");
  EXPECT_NE(ErrorOf(s + "seeds: [1, 1]\n").find("bad.yaml:2:12: seed 1 appears twice"), std::string::npos);
  EXPECT_NE(ErrorOf(s + "seeds: 0\n").find("bad.yaml:2:8"), std::string::npos);
  EXPECT_NE(ErrorOf(s + "grid: {duration_s: 3}\n").find("bad.yaml:2:20: key 'grid.duration_s' expected a non-empty list"),
            std::string::npos);
  EXPECT_NE(ErrorOf(s + "grid: {duration_s: [3]}\nfixed: {duration_s: 4}\n").find("is both fixed and in the grid"),
            std::string::npos);
  EXPECT_NE(ErrorOf(s + "metrics: [ate.rmse_m]\nbest: {b: max}\n").find("bad.yaml:3:8: 'b' is not one of the metrics"),
            std::string::npos);
  EXPECT_NE(ErrorOf(s + "metrics: [ate.rmse_m]\nbest: {ate.rmse_m: most}\n").find("bad.yaml:3:20"), std::string::npos);
  // A metric no run writes (a typo) is named before anything runs, with the nearest key.
  EXPECT_NE(ErrorOf(s + "metrics: [ate.rmse_m, ate.rmse]\n")
                .find("bad.yaml:2:23: 'ate.rmse' is no metrics.json key (did you mean 'ate.rmse_m'?)"),
            std::string::npos)
      << ErrorOf(s + "metrics: [ate.rmse_m, ate.rmse]\n");
  EXPECT_NE(ErrorOf(s + "metrics: [zzzz]\n").find("'zzzz' is no metrics.json key (the keys are listed in DESIGN.md"),
            std::string::npos)
      << ErrorOf(s + "metrics: [zzzz]\n");
  EXPECT_NE(ErrorOf("scenarios: [nowhere.yaml]\n").find("bad.yaml:1:13: scenario file not found"), std::string::npos);
  EXPECT_NE(ErrorOf("seeds: [1]\n").find("missing required key 'scenarios'"), std::string::npos);
  // A key or value that `viqu run --set` would reject: the point and the override are named.
  const std::string unknown = ErrorOf(s + "grid: {sensors.camera.nosie_std: [1]}\n");
  EXPECT_NE(unknown.find("bad.yaml: point p0000"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("unknown key 'sensors.camera.nosie_std'"), std::string::npos) << unknown;
  const std::string range = ErrorOf(s + "grid: {sensors.camera.fovy_deg: [60, 179]}\n");
  EXPECT_NE(range.find("point p0001"), std::string::npos) << range;
  EXPECT_NE(range.find("--set sensors.camera.fovy_deg=179"), std::string::npos) << range;
  // ... and one the SLAM settings would reject when the run starts (the scenario checks only
  // the key and its kind): named now, not after the other points have run.
  const std::string weight = ErrorOf(s + "grid: {slam.stereo.near_right_weight_ba: [0.03, 2]}\n");
  EXPECT_NE(weight.find("point p0001"), std::string::npos) << weight;
  EXPECT_NE(weight.find("--set slam.stereo.near_right_weight_ba=2: key 'stereo.near_right_weight_ba' expected a number in [0, 1]"),
            std::string::npos) << weight;
}

// A complete run folder with the given metrics.json and exit code.
void MakeRun(const fs::path& dir, const std::string& metrics_json, int exit_code) {
  RunFolderWriter w(dir.string(), false, "test");
  std::ofstream(fs::path(w.path()) / "metrics.json") << metrics_json;
  w.Complete(exit_code);
}

std::vector<std::vector<std::string>> ReadCsv(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> row;
    std::stringstream ss(line);
    for (std::string field; std::getline(ss, field, ',');) row.push_back(field);
    if (!line.empty() && line.back() == ',') row.push_back("");
    rows.push_back(row);
  }
  return rows;
}

TEST_F(SweepTest, TablesComeFromTheRunFoldersAlone) {
  const std::string path = Write("s.yaml", "scenarios: [" + kScenario + "]\nseeds: [1, 2, 3]\n"
                                           "grid: {sensors.camera.noise_std: [1, 4]}\n"
                                           "metrics: [ate.rmse_m, dynamic.recall]\nbest: {dynamic.recall: max}\n");
  const SweepSpec spec = LoadSweepSpec(path);
  const std::vector<SweepPoint> points = ExpandSweep(spec);
  ASSERT_EQ(points.size(), 6u);
  // noise 1: ATE 0.1, 0.2, 0.3 (recall 0.5 each); noise 4: ATE 0.4, a failed run, and a point
  // that never finished (no folder).
  const double ate[] = {0.1, 0.2, 0.3, 0.4};
  for (int i = 0; i < 4; ++i) {
    MakeRun(dir_ / "points" / points[i].id,
            "{\"ate\": {\"rmse_m\": " + std::to_string(ate[i]) + "}, \"dynamic\": {\"recall\": 0.5},"
            " \"timing\": {\"wall_time_s\": 12.5}}\n", 0);
  }
  // The robot fell early in the failed run: a short, flattering ATE that must not count.
  MakeRun(dir_ / "points" / points[4].id, "{\"robot\": {\"fell\": true}, \"ate\": {\"rmse_m\": 0.001}}\n", 1);
  std::vector<PointOutcome> outcomes;
  for (const SweepPoint& p : points) outcomes.push_back(ReadPointOutcome(spec, (dir_ / "points" / p.id).string()));
  EXPECT_EQ(outcomes[0].status, "ok");
  EXPECT_EQ(outcomes[4].status, "failed");
  EXPECT_EQ(outcomes[4].exit_code, "1");
  EXPECT_EQ(outcomes[5].status, "missing");
  const std::vector<std::string> best = WriteSweepTables(spec, points, outcomes, dir_.string());

  const auto results = ReadCsv(dir_ / "results.csv");
  ASSERT_EQ(results.size(), 7u);
  EXPECT_EQ(results[0], (std::vector<std::string>{"id", "scenario", "seed", "sensors.camera.noise_std", "ate.rmse_m",
                                                  "dynamic.recall", "exit_code", "status", "wall_s"}));
  EXPECT_EQ(results[1], (std::vector<std::string>{"p0000", "static_room", "1", "1", "0.100000", "0.5", "0", "ok", "12.5"}));
  EXPECT_EQ(results[5], (std::vector<std::string>{"p0004", "static_room", "2", "4", "0.001", "", "1", "failed", ""}));
  EXPECT_EQ(results[6], (std::vector<std::string>{"p0005", "static_room", "3", "4", "", "", "", "missing", ""}));

  const auto summary = ReadCsv(dir_ / "summary.csv");
  ASSERT_EQ(summary.size(), 3u);
  EXPECT_EQ(summary[0][4], "ate.rmse_m.mean");
  // noise 1: mean 0.2, sample std 0.1, min 0.1, max 0.3 over 3 seeds.
  EXPECT_EQ(summary[1][0], "static_room");
  EXPECT_EQ(summary[1][1], "1");
  EXPECT_EQ(summary[1][2], "3");
  EXPECT_EQ(summary[1][3], "3");
  EXPECT_NEAR(std::stod(summary[1][4]), 0.2, 1e-9);
  EXPECT_NEAR(std::stod(summary[1][5]), 0.1, 1e-9);
  EXPECT_NEAR(std::stod(summary[1][6]), 0.1, 1e-9);
  EXPECT_NEAR(std::stod(summary[1][7]), 0.3, 1e-9);
  EXPECT_EQ(summary[1][8], "3");
  // noise 4: one value, 0.4; one of three points ok.
  EXPECT_EQ(summary[2][3], "1");
  EXPECT_NEAR(std::stod(summary[2][4]), 0.4, 1e-9);
  EXPECT_EQ(summary[2][5], "");  // no sample std of one value
  EXPECT_EQ(summary[2][8], "1");
  ASSERT_EQ(best.size(), 2u);
  EXPECT_NE(best[0].find("ate.rmse_m (min): 0.2 mean over 3 seed(s) at static_room, sensors.camera.noise_std=1"),
            std::string::npos) << best[0];
  EXPECT_NE(best[1].find("dynamic.recall (max): 0.5"), std::string::npos) << best[1];
}

TEST(SweepCsv, QuotesFieldsThatNeedIt) {
  EXPECT_EQ(CsvField("plain"), "plain");
  EXPECT_EQ(CsvField("[0.5, 0.5]"), "\"[0.5, 0.5]\"");
  EXPECT_EQ(CsvField("say \"hi\""), "\"say \"\"hi\"\"\"");
}

}  // namespace
}  // namespace viqu::app
