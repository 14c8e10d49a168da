// ProgressLine: throttled redraws, silent when disabled, newline at the end.
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "runner/progress.h"

namespace viqu::runner {
namespace {

// Captures what the progress line writes.
class Capture {
 public:
  Capture() : file_(std::tmpfile()) {}
  ~Capture() { std::fclose(file_); }
  std::FILE* file() { return file_; }
  std::string Text() {
    std::fflush(file_);
    std::rewind(file_);
    std::string s;
    for (int c; (c = std::fgetc(file_)) != EOF;) s += static_cast<char>(c);
    return s;
  }

 private:
  std::FILE* file_;
};

TEST(ProgressLine, DrawsAtMostFourTimesASecondAndEndsTheLine) {
  Capture cap;
  {
    ProgressLine p(40.0, cap.file(), true);
    p.UpdateAt(0.5, 0.5);   // drawn
    p.UpdateAt(0.6, 0.6);   // too soon
    p.UpdateAt(0.8, 0.8);   // drawn
    p.UpdateAt(12.3, 14.0);  // drawn
    p.Finish();
    p.Finish();             // once only
  }
  const std::string text = cap.Text();
  EXPECT_EQ(text,
            "\r sim 0.5/40.0 s  RTF 1.00x "
            "\r sim 0.8/40.0 s  RTF 1.00x "
            "\r sim 12.3/40.0 s  RTF 0.88x "
            "\r sim 12.3/40.0 s  RTF 0.88x \n");
}

TEST(ProgressLine, SilentWhenDisabled) {
  Capture cap;
  {
    ProgressLine p(10.0, cap.file(), false);
    p.UpdateAt(1.0, 1.0);
    p.Update(2.0);
  }
  EXPECT_EQ(cap.Text(), "");
}

TEST(ProgressLine, NoNewlineWhenNothingWasDrawn) {
  Capture cap;
  { ProgressLine p(10.0, cap.file(), true); }
  EXPECT_EQ(cap.Text(), "");
}

}  // namespace
}  // namespace viqu::runner
