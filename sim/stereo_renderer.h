#pragma once
// Off-screen stereo rendering of the model cameras `cam_left` and `cam_right` through EGL:
// RGB for both, metric depth and instance segmentation for the left camera.
#include <memory>
#include <vector>

#include <mujoco/mujoco.h>

#include "sim/egl_context.h"
#include "sim/segmentation_ids.h"
#include "slam/measurements/stereo_frame.h"

namespace viqu::sim {

// What to render and how. The defaults are the lean set for software rendering (llvmpipe):
// shadows, reflections, skybox, haze and fog each cost time and add nothing to SLAM.
struct RenderOptions {
  int width = 640;             // image width (px); at most the model's <visual><global offwidth>
  int height = 480;            // image height (px); at most <visual><global offheight>
  bool depth = true;           // render left metric depth (StereoFrame::left_depth_m)
  bool segmentation = true;    // render left instance ids (StereoFrame::left_instance_id)
  bool shadows = false;        // shadow mapping for lights with castshadow (one extra pass per light)
  bool reflections = false;    // reflective planes (one extra scene pass per reflective plane)
  bool skybox = false;         // draw the skybox texture
  bool haze = false;           // horizon haze at the edge of planes
  int max_lights = -1;         // use at most this many scene lights, headlight first; -1 = all
  // Clipping planes of the cameras (m); <= 0 = the model's vis.map.znear/zfar * stat.extent.
  // Explicit by default: the model's planes scale with the world's size, and a camera 7 cm above
  // the floor sees floor 0.1 m ahead at its bottom row, which a near plane of 1% of a room's
  // extent clips away. Depth resolution at z is about z^2 / z_near * 2^-24 (24-bit depth).
  double z_near_m = 0.01;
  double z_far_m = 100.0;
  // MSAA samples of the off-screen buffer; -1 = the model's <visual><quality offsamples> (MuJoCo
  // default 4). Default 0: 4x MSAA makes a software-rendered 640x480 stereo frame about 2.5x
  // slower, and its depth comes from one sample off the pixel centre (bench/bench_render.cc).
  int multisamples = 0;
  EglContext::Platform egl_platform = EglContext::Platform::kAuto;  // where to get the GL context
};

// Renders stereo frames of a model. Owns its EGL context, MuJoCo scene and render context.
// Use from one thread; several renderers may live in one process (each Render makes its own
// context current).
class StereoRenderer {
 public:
  // Throws viqu::RunError if the cameras cam_left/cam_right are missing, the requested size
  // exceeds the model's off-screen buffer (vis.global.offwidth/offheight), the two cameras have
  // different fovy, or EGL / the off-screen buffer cannot be set up. Throws viqu::InputError for
  // badly named root bodies (see SegmentationIds).
  StereoRenderer(const mjModel* m, const RenderOptions& opt);
  ~StereoRenderer();
  StereoRenderer(const StereoRenderer&) = delete;
  StereoRenderer& operator=(const StereoRenderer&) = delete;

  // Renders the cameras at the state `d` (kinematics must be current: mj_forward/mj_step done).
  // `m` must be the model given to the constructor. Fills every field of `out` with newly
  // allocated images (images of an earlier frame that the caller still holds are not touched);
  // depth and instance ids stay empty when disabled in the options.
  void Render(const mjModel* m, mjData* d, StereoFrame* out);

  // Pinhole intrinsics of both cameras, pixel centres at integer coordinates.
  const PinholeIntrinsics& intrinsics() const { return intrinsics_; }

  // Distance between cam_left and cam_right in the model (m).
  double baseline_m() const { return baseline_m_; }

  // The instance table (fixed for the model).
  const SegmentationIds& segmentation_ids() const { return ids_; }

  // Where the GL context lives (EglContext::Description()).
  const std::string& device_description() const { return egl_->Description(); }

 private:
  // Updates the scene for camera `cam_id`, renders it and reads RGB (and depth if `depth`) into
  // the bottom-up buffers.
  void RenderCamera(const mjModel* m, mjData* d, int cam_id, bool depth);
  void RenderSegmentation(const mjModel* m, StereoFrame* out);
  void ApplySceneFlags();
  // Sets the clipping planes of the scene's GL cameras to z_near_/z_far_ and checks that the
  // frustum matches the intrinsics.
  void SetClipPlanes();

  RenderOptions opt_;
  int nbody_ = 0, ngeom_ = 0, ncam_ = 0;  // sizes of the model this renderer was made for
  int cam_left_ = -1, cam_right_ = -1;  // camera ids in the model
  PinholeIntrinsics intrinsics_;
  double baseline_m_ = 0;               // (m)
  float z_near_ = 0, z_far_ = 0;        // clipping planes of the cameras (m)
  SegmentationIds ids_;

  std::unique_ptr<EglContext> egl_;
  mjvScene scn_;
  mjvOption vopt_;
  mjvCamera cam_;
  mjrContext con_;
  mjrRect viewport_;

  std::vector<unsigned char> rgb_buf_;  // bottom-up RGB read-back (W*H*3)
  std::vector<float> depth_buf_;        // bottom-up window depth in [0, 1] (W*H)
  std::vector<uint16_t> seg_lut_;       // instance id per segmentation colour (segid + 1)
};

}  // namespace viqu::sim
