#include "runner/progress.h"

#include <unistd.h>

namespace viqu::runner {
namespace {
constexpr double kRedrawPeriodS = 0.25;  // about 4 Hz
}  // namespace

ProgressLine::ProgressLine(double total_sim_s)
    : ProgressLine(total_sim_s, stderr, ::isatty(STDERR_FILENO) == 1) {}

ProgressLine::ProgressLine(double total_sim_s, std::FILE* out, bool enabled)
    : total_sim_s_(total_sim_s), out_(out), enabled_(enabled), start_(std::chrono::steady_clock::now()) {}

ProgressLine::~ProgressLine() { Finish(); }

double ProgressLine::WallSeconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void ProgressLine::Update(double sim_s) {
  if (!enabled_) return;
  UpdateAt(sim_s, WallSeconds());
}

void ProgressLine::UpdateAt(double sim_s, double wall_s) {
  last_sim_s_ = sim_s;
  last_wall_s_ = wall_s;
  if (!enabled_ || finished_) return;
  if (last_draw_wall_s_ >= 0 && wall_s - last_draw_wall_s_ < kRedrawPeriodS) return;
  Draw(sim_s, wall_s);
}

void ProgressLine::Draw(double sim_s, double wall_s) {
  const double rtf = wall_s > 0 ? sim_s / wall_s : 0.0;
  if (note_[0] == '\0') {
    std::fprintf(out_, "\r sim %.1f/%.1f s  RTF %.2fx ", sim_s, total_sim_s_, rtf);
  } else {
    std::fprintf(out_, "\r sim %.1f/%.1f s  RTF %.2fx  %-12s", sim_s, total_sim_s_, rtf, note_);  // padded: overwrite a longer note
  }
  std::fflush(out_);
  last_draw_wall_s_ = wall_s;
}

void ProgressLine::Finish() {
  if (finished_) return;
  finished_ = true;
  if (!enabled_) return;
  if (last_draw_wall_s_ >= 0) {
    Draw(last_sim_s_, last_wall_s_);
    std::fputc('\n', out_);
    std::fflush(out_);
  }
}

}  // namespace viqu::runner
