#pragma once
#include <string>
#include <vector>

#include "scenario/scenario.h"

namespace viqu {

// Loads a scenario YAML file (DESIGN.md "Scenario schema" plus the keys documented in
// scenario.h) with strict validation. `overrides` are "key.path=value" strings from `--set`,
// applied to the YAML tree before validation; the value is parsed as YAML ("[]", "10",
// "{a: 1}"), list elements are addressed by index ("obstacles.0.speed_mps=1").
//
// Every problem throws InputError with a message that starts with "FILE:LINE:COL" (or with the
// override that caused it): unknown key, wrong type, missing required key (name, world,
// robot.model, obstacles[].name, obstacles[].path), out-of-range value, missing referenced
// file. `world`, `robot.model` and `slam.config` are relative to the scenario file and come back
// as absolute paths; the robot's URDF must exist beside its MJCF with the same stem.
Scenario LoadScenario(const std::string& path, const std::vector<std::string>& overrides = {});

// The fully resolved scenario as YAML (every key, absolute paths), for DIR/scenario.yaml.
// LoadScenario of the written text gives back an equal Scenario (except `source_file`).
std::string ScenarioToYaml(const Scenario& scenario);

}  // namespace viqu
