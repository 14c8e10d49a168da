#include "slam/io/frame_skip_policy.h"

#include <cstdio>

#include "common/errors.h"

namespace viqu::io {

void FrameSkipPolicy::Bad(const std::string& why) {
  if (!any_good_) throw InputError(why + "; the first frame is not skipped: check the dataset");
  if (last_bad_) throw InputError(why + "; the second unreadable frame in a row: the dataset looks broken");
  if (max_skipped_ == 0) throw InputError(why + " (--skip-bad-frames skips a lone unreadable frame)");
  if (skipped_ >= max_skipped_) {
    throw InputError(why + "; " + std::to_string(skipped_) + " unreadable frame(s) skipped already, as many as --skip-bad-frames " +
                     std::to_string(max_skipped_) + " allows: check the dataset, or allow more");
  }
  last_bad_ = true;
  ++skipped_;
  std::fprintf(stderr, "viqu: warning: %s; frame skipped\n", why.c_str());
}

}  // namespace viqu::io
