#include "apps/sweep_command.h"

#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <thread>
#include <vector>

#include "apps/sweep_spec.h"
#include "apps/sweep_tables.h"
#include "common/atomic_file.h"
#include "common/child_process.h"
#include "common/errors.h"
#include "common/output_lock.h"
#include "common/run_folder.h"
#include "common/stop_signal.h"

namespace viqu::app {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// How long a point stopped for its timeout (or the sweep's stop) gets between SIGTERM and
// SIGKILL: a run finishes its outputs at the next physics step, well within this.
constexpr double kStopGraceS = 10;
// How often the scheduler looks at its children (s).
constexpr double kPollS = 0.05;

// Shell quoting for the manifest.
std::string ShellQuote(const std::string& s) {
  if (!s.empty() && s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./=:,+@%") ==
                        std::string::npos) {
    return s;
  }
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::vector<std::string> PointArgs(const std::string& viqu_exe, const SweepPoint& p, const std::string& dir) {
  std::vector<std::string> a = {viqu_exe, "run", p.scenario, "--out", dir + "/points/" + p.id};
  for (const std::string& s : p.sets) {
    a.push_back("--set");
    a.push_back(s);
  }
  return a;
}

std::string Duration(double s) {
  char buf[32];
  if (s >= 120) {
    std::snprintf(buf, sizeof buf, "%.0f min", s / 60);
  } else {
    std::snprintf(buf, sizeof buf, "%.0f s", s);
  }
  return buf;
}

void WritePlan(const SweepSpec& spec, const std::vector<SweepPoint>& points, const std::string& viqu_exe,
               const std::string& dir) {
  WriteFileAtomic(dir + "/sweep.yaml", "# the sweep as resolved by viqu (absolute scenario paths)\n" + SweepSpecToYaml(spec));
  std::string manifest;
  // A point's time limit, as the local runner keeps it: SIGTERM at timeout_s (the run ends at a
  // step boundary, marked incomplete), SIGKILL 10 s later (coreutils' timeout).
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.9g", spec.timeout_s);
  const std::string limit = spec.timeout_s > 0 ? "timeout -k 10 " + std::string(seconds) + " " : "";
  for (const SweepPoint& p : points) {
    std::string line;
    for (const std::string& a : PointArgs(viqu_exe, p, dir)) line += (line.empty() ? "" : " ") + ShellQuote(a);
    manifest += limit + line + " > " + ShellQuote(dir + "/logs/" + p.id + ".log") + " 2>&1\n";
  }
  WriteFileAtomic(dir + "/manifest.txt", manifest);
}

// Runs the points not yet complete; fills outcomes[i] of those it ran. Returns the stop signal
// (0 when every point ran).
int RunPoints(const SweepSpec& spec, const std::vector<SweepPoint>& points, const std::vector<bool>& todo,
              const std::string& viqu_exe, const std::string& dir, int jobs, std::vector<PointOutcome>* outcomes) {
  struct Running {
    size_t index = 0;
    Clock::time_point start;
    bool terminated = false;  // SIGTERM sent (timeout or stop)
    bool timed_out = false;
    Clock::time_point term_time;
  };
  std::map<pid_t, Running> running;
  size_t next = 0, total = 0, done = 0, failed = 0;
  for (bool t : todo) total += t ? 1 : 0;
  const auto sweep_start = Clock::now();
  int stop = 0;
  while (true) {
    if (stop == 0) stop = StopSignal();
    while (stop == 0 && static_cast<int>(running.size()) < jobs && next < points.size()) {
      if (!todo[next]) {
        ++next;
        continue;
      }
      const SweepPoint& p = points[next];
      const pid_t pid = StartProcess(PointArgs(viqu_exe, p, dir), dir + "/logs/" + p.id + ".log");
      Running r;
      r.index = next;
      r.start = Clock::now();
      running[pid] = r;
      ++next;
    }
    if (running.empty()) break;
    const auto now = Clock::now();
    for (auto& [pid, r] : running) {
      const double age = std::chrono::duration<double>(now - r.start).count();
      if (!r.terminated && (stop != 0 || (spec.timeout_s > 0 && age > spec.timeout_s))) {
        r.timed_out = stop == 0;
        r.terminated = true;
        r.term_time = now;
        ::kill(pid, SIGTERM);
      } else if (r.terminated && std::chrono::duration<double>(now - r.term_time).count() > kStopGraceS) {
        ::kill(pid, SIGKILL);
      }
    }
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, WNOHANG);
    if (pid <= 0) {
      std::this_thread::sleep_for(std::chrono::duration<double>(kPollS));
      continue;
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const Running r = it->second;
    running.erase(it);
    const SweepPoint& p = points[r.index];
    PointOutcome o = ReadPointOutcome(spec, dir + "/points/" + p.id);
    const int code = ExitCodeOf(status);
    o.exit_code = std::to_string(code);
    if (r.timed_out && o.status != "ok") {  // a run that completed before the SIGTERM counts as ok
      o.status = "timeout";
    } else if (o.status == "missing") {
      o.status = "failed";
    }
    (*outcomes)[r.index] = o;
    ++done;
    if (o.status != "ok") ++failed;
    const double elapsed = std::chrono::duration<double>(Clock::now() - sweep_start).count();
    const double left = done > 0 ? elapsed / done * (total - done) : 0;
    std::fprintf(stderr, "viqu sweep: %zu/%zu done (%zu failed), %zu running, about %s left; %s %s (exit %d)\n", done,
                 total, failed, running.size(), Duration(left).c_str(), p.id.c_str(), o.status.c_str(), code);
  }
  return stop;
}

}  // namespace

namespace {

// The sweep's seeds replace each scenario's own `seed`: said in the printed plan, since a
// `seeds: 2` sweep of a scenario with seed 7 runs seeds 1 and 2, never 7.
std::string SeedsLine(const SweepSpec& spec) {
  std::string list;
  for (size_t i = 0; i < spec.seeds.size() && i < 10; ++i) list += (i ? ", " : "") + std::to_string(spec.seeds[i]);
  if (spec.seeds.size() > 10) list += ", ... (" + std::to_string(spec.seeds.size()) + " seeds)";
  return "seeds " + list + " (each point runs with --set seed=N: the scenarios' own seed keys are not used)";
}

}  // namespace

int RunSweepCommand(const SweepArgs& args, const std::string& viqu_exe) {
  const bool collect = !args.collect_dir.empty();
  const std::string dir = collect ? args.collect_dir
                                  : (args.out_dir.empty() ? "sweeps/" + fs::path(args.sweep_file).stem().string() : args.out_dir);
  const SweepSpec spec = LoadSweepSpec(collect ? dir + "/sweep.yaml" : args.sweep_file);
  const std::vector<SweepPoint> points = ExpandSweep(spec);
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw InputError("--out " + dir + " exists and is not a folder");
  // One sweep process per folder (a run, a resume, an emit or a collect); the points' own runs
  // lock their points/<id> folders, so a Slurm array's tasks do not hold this one.
  const OutputLock lock(dir, std::string("viqu sweep ") + (collect ? "--collect " + dir : args.sweep_file + " --out " + dir));
  if (!collect) {
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw InputError("--out " + dir + " exists and is not a folder");
    if (fs::exists(dir + "/sweep.yaml", ec) && !args.resume && args.emit.empty()) {
      throw InputError("--out " + dir + " holds a sweep already: pass --resume to finish it, or choose another folder");
    }
    // A sweep folder belongs to one sweep: resuming (or emitting) with another grid would put old
    // runs under new values.
    if (fs::exists(dir + "/sweep.yaml", ec)) {
      const SweepSpec stored = LoadSweepSpec(dir + "/sweep.yaml");
      if (SweepSpecToYaml(stored) != SweepSpecToYaml(spec)) {
        throw InputError(args.sweep_file + ": differs from the sweep that " + dir + " holds (" + dir +
                         "/sweep.yaml); use another --out");
      }
    }
    fs::create_directories(dir + "/points", ec);
    fs::create_directories(dir + "/logs", ec);
    if (ec) throw InputError("cannot create sweep folder " + dir + ": " + ec.message());
    WritePlan(spec, points, fs::absolute(viqu_exe).string(), fs::absolute(dir).lexically_normal().string());
  }
  if (!args.emit.empty()) {
    if (args.emit == "slurm") {
      const std::string abs = fs::absolute(dir).lexically_normal().string();
      std::string sbatch =
          "#!/bin/bash\n"
          "# A Slurm job array over the points of this sweep: task i runs line i + 1 of manifest.txt.\n"
          "# Submit with `sbatch " + ShellQuote(abs + "/sweep.sbatch") + "`; afterwards `viqu sweep --collect " +
          ShellQuote(abs) + "`.\n"
          "#SBATCH --job-name=viqu-sweep\n"
          "#SBATCH --array=0-" + std::to_string(points.size() - 1) + "\n"
          // A run keeps two threads busy (the simulation and renderer, the estimator).
          "#SBATCH --cpus-per-task=2\n" +
          (spec.timeout_s > 0
               ? "#SBATCH --time=" + std::to_string(static_cast<long>(std::ceil((spec.timeout_s + 10) / 60.0)) + 1) + "\n"
               : std::string()) +
          "#SBATCH --output=" + abs + "/logs/slurm-%a.out\n"
          "set -euo pipefail\n"
          "line=$(sed -n \"$((SLURM_ARRAY_TASK_ID + 1))p\" " + ShellQuote(abs + "/manifest.txt") + ")\n"
          "eval \"$line\"\n";
      WriteFileAtomic(dir + "/sweep.sbatch", sbatch);
      std::printf("viqu sweep: %zu points: %s/manifest.txt and %s/sweep.sbatch (then viqu sweep --collect %s)\n",
                  points.size(), dir.c_str(), dir.c_str(), dir.c_str());
      std::printf("viqu sweep: %s\n", SeedsLine(spec).c_str());
    } else {
      std::printf("viqu sweep: %zu points: %s/manifest.txt, one command per line (then viqu sweep --collect %s)\n",
                  points.size(), dir.c_str(), dir.c_str());
      std::printf("viqu sweep: %s\n", SeedsLine(spec).c_str());
    }
    return 0;
  }

  std::vector<PointOutcome> outcomes(points.size());
  std::vector<bool> todo(points.size(), !collect);
  size_t skipped = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const std::string run_dir = dir + "/points/" + points[i].id;
    if (collect || (args.resume && IsCompleteRunFolder(run_dir))) {
      outcomes[i] = ReadPointOutcome(spec, run_dir);
      todo[i] = false;
      ++skipped;
    }
  }
  int stop = 0;
  if (!collect) {
    std::fprintf(stderr, "viqu sweep: %zu points (%zu complete already), %d at once, folder %s\n", points.size(), skipped,
                 args.jobs, dir.c_str());
    std::fprintf(stderr, "viqu sweep: %s\n", SeedsLine(spec).c_str());
    stop = RunPoints(spec, points, todo, viqu_exe, dir, args.jobs, &outcomes);
  }
  const std::vector<std::string> best = WriteSweepTables(spec, points, outcomes, dir);
  size_t ok = 0;
  for (const PointOutcome& o : outcomes) ok += o.status == "ok" ? 1 : 0;
  std::printf("viqu sweep: %zu of %zu points ok; %s/results.csv, %s/summary.csv\n", ok, points.size(), dir.c_str(),
              dir.c_str());
  for (const std::string& line : best) std::printf("best %s\n", line.c_str());
  if (stop != 0) {
    std::fprintf(stderr, "viqu sweep: stopped by %s; `viqu sweep %s --out %s --resume` finishes it\n", SignalName(stop),
                 args.sweep_file.c_str(), dir.c_str());
    return ExitCodeForSignal(stop);
  }
  return 0;
}

}  // namespace viqu::app
