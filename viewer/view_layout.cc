#include "viewer/view_layout.h"

#include <algorithm>
#include <cmath>

namespace viqu::viewer {

ViewLayout LayoutFor(int fb_width, int fb_height, int image_width, int image_height) {
  ViewLayout l;
  fb_width = std::max(fb_width, 0);
  fb_height = std::max(fb_height, 0);
  if (image_width <= 0 || image_height <= 0 || fb_width == 0 || fb_height == 0) {
    l.scene = {0, 0, fb_width, fb_height};
    l.image_scale = 0;
    return l;
  }
  l.image_scale = std::min({1.0, 0.5 * fb_width / image_width, 0.75 * fb_height / image_height});
  const int w = static_cast<int>(std::floor(image_width * l.image_scale));
  const int h = static_cast<int>(std::floor(image_height * l.image_scale));
  l.image = {fb_width - w, fb_height - h, w, h};
  l.status = {fb_width - w, 0, w, fb_height - h};
  l.scene = {0, 0, fb_width - w, fb_height};
  return l;
}

}  // namespace viqu::viewer
