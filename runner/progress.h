#pragma once
#include <chrono>
#include <cstdio>

namespace viqu::runner {

// A one-line progress display on stderr: "\r sim 12.3/40.0 s  RTF 0.87x", redrawn at most about
// four times a second, ended by a newline in Finish(). Silent when stderr is not a terminal, so
// logs and CI output stay clean.
class ProgressLine {
 public:
  // Shows progress towards `total_sim_s` seconds of simulated time; enabled iff stderr is a tty.
  explicit ProgressLine(double total_sim_s);
  // For tests: explicit stream and switch.
  ProgressLine(double total_sim_s, std::FILE* out, bool enabled);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // Reports the current simulated time; draws when 0.25 s of wall time passed since the last draw.
  void Update(double sim_s);
  // As Update, with the wall-clock seconds since construction given (for tests).
  void UpdateAt(double sim_s, double wall_s);
  // Draws the final state and ends the line (once; also called by the destructor).
  void Finish();

  // A short word shown after the rate (e.g. the SLAM tracking status); must outlive the line.
  void SetNote(const char* note) { note_ = note; }

  bool enabled() const { return enabled_; }

 private:
  void Draw(double sim_s, double wall_s);
  double WallSeconds() const;

  double total_sim_s_;                                // run length (s of simulated time)
  std::FILE* out_;                                    // stream drawn to
  bool enabled_;                                      // draw at all
  std::chrono::steady_clock::time_point start_;       // wall clock at construction
  double last_draw_wall_s_ = -1;                      // wall time of the last draw (s); <0: never
  double last_sim_s_ = 0;                             // latest simulated time reported (s)
  double last_wall_s_ = 0;                            // wall time of that report (s)
  bool finished_ = false;                             // Finish() ran
  const char* note_ = "";                             // shown after the rate
};

}  // namespace viqu::runner
