#pragma once
#include <string>
#include <vector>

namespace viqu::app {

// `viqu report DIR [--x KEY] [--y KEY] [--metric M]`: runs tools/report.py (Debian's
// /usr/bin/python3 with matplotlib) on a run folder or a sweep folder; the plots go to
// DIR/plots/. `args` are passed on after DIR. Returns the tool's exit code (2: bad input).
int RunReport(const std::string& dir, const std::vector<std::string>& args);

}  // namespace viqu::app
