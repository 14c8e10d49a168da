#pragma once
// Where the viewer draws what in its window: the 3D scene on the left, the camera image with
// SLAM's overlays at the top right, a status panel below it. Pure arithmetic, testable.

namespace viqu::viewer {

// A rectangle in framebuffer pixels with OpenGL's bottom-left origin (as mjrRect).
struct PixelRect {
  int left = 0, bottom = 0, width = 0, height = 0;
};

struct ViewLayout {
  PixelRect scene;   // free camera on the world
  PixelRect image;   // the camera image, scaled by image_scale
  PixelRect status;  // text under the image
  double image_scale = 1;
};

// The layout for a framebuffer of fb_width x fb_height and camera images of image_width x
// image_height. The image keeps its aspect ratio and is never enlarged; it takes at most half
// the width and three quarters of the height, so that the scene keeps at least half the window.
ViewLayout LayoutFor(int fb_width, int fb_height, int image_width, int image_height);

}  // namespace viqu::viewer
