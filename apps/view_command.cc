#include "apps/view_command.h"

#include <cstdio>

#include "runner/run_scenario.h"
#include "scenario/scenario_loader.h"
#ifdef VIQU_HAVE_VIEWER
#include "viewer/run_viewer.h"
#endif

namespace viqu::app {

int RunViewCommand(const ViewArgs& args, const std::string& command_line) {
#ifdef VIQU_HAVE_VIEWER
  const Scenario scenario = LoadScenario(args.scenario, args.sets);
  runner::RunOptions options = args.options;
  options.command_line = command_line;
  if (options.out_dir.empty()) options.out_dir = "runs/" + scenario.name + "-view";
  viewer::ViewerOptions vopt;
  vopt.speed = args.speed;
  vopt.start_paused = args.paused;
  vopt.exit_at_end = args.exit_at_end;
  vopt.screenshot_path = args.screenshot;
  vopt.title = "viqu view: " + scenario.name;
  viewer::RunViewer view(vopt);  // opens the window first: without a display nothing is written
  return runner::RunScenario(scenario, options, &view);
#else
  (void)args;
  (void)command_line;
  std::fprintf(stderr,
               "viqu: this viqu was built without the viewer (GLFW was not found when it was configured, or "
               "-DVIQU_VIEWER=OFF): install libglfw3-dev, then run scripts/setup.sh again\n");
  return 2;
#endif
}

}  // namespace viqu::app
