#pragma once
#include "apps/cli.h"

namespace viqu::app {

// `viqu eval EST GT [--json] [--sim3] [--delta N | --delta-m D]`: ATE (SE(3) or Sim(3) Umeyama,
// associate.py matching within 0.02 s) and RPE (N associated frames or D metres apart) of two TUM trajectories, printed as text or one JSON object with
// the keys of metrics.json. Returns the exit code; throws InputError for bad files.
int RunEval(const EvalArgs& args);

}  // namespace viqu::app
