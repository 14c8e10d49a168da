#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace viqu::io {

// What a reader does with a frame whose image files cannot be read. By default any such frame is
// bad input: InputError naming the file (exit 2), since a replay that quietly drops frames is not
// the run it replays. With Allow(n) (`viqu slam --skip-bad-frames [N]`) up to n single bad frames
// among good ones (a truncated file in a long sequence) are skipped with a warning on stderr and
// counted; a bad first frame, two bad frames in a row, or one more than n still point at a broken
// dataset: InputError.
class FrameSkipPolicy {
 public:
  void Allow(int max_skipped) { max_skipped_ = max_skipped; }
  // The frame was read.
  void Good() {
    any_good_ = true;
    last_bad_ = false;
  }
  // The frame cannot be read (`why` names the file): warns and returns (the caller skips the
  // frame) when skipping is allowed and the frame is a lone bad one, or throws InputError(why + ...).
  void Bad(const std::string& why);

  int skipped() const { return skipped_; }

 private:
  int max_skipped_ = 0;    // lone bad frames that may be skipped
  bool any_good_ = false;  // a frame was read
  bool last_bad_ = false;  // the frame before this one could not be read
  int skipped_ = 0;        // frames skipped so far
};

// The next frame that `read(items[i], &frame, &why)` manages to read, from items[*next] on;
// unreadable ones are handed to `skip` (warned about and skipped, or InputError). *frame is left
// untouched by a skipped frame. Returns false after the last item.
template <class Item, class Frame, class Read>
bool NextReadable(const std::vector<Item>& items, size_t* next, FrameSkipPolicy* skip, Frame* frame, Read read) {
  while (*next < items.size()) {
    const Item& item = items[(*next)++];
    std::string why;
    Frame f;
    if (!read(item, &f, &why)) {
      skip->Bad(why);
      continue;
    }
    *frame = std::move(f);
    skip->Good();
    return true;
  }
  return false;
}

}  // namespace viqu::io
