#include "sim/stereo_renderer.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/errors.h"
#include "sim/mujoco_handles.h"

namespace viqu::sim {
namespace {

constexpr const char* kLeftCamera = "cam_left";
constexpr const char* kRightCamera = "cam_right";
constexpr int kExtraSceneGeoms = 1000;  // room for decor geoms beyond the model's own

int CameraIdOrThrow(const mjModel* m, const char* name) {
  const int id = mj_name2id(m, mjOBJ_CAMERA, name);
  if (id < 0) {
    throw RunError(std::string("stereo renderer: the model has no camera named '") + name +
                   "' (needs cam_left and cam_right)");
  }
  return id;
}

// Pinhole intrinsics of a MuJoCo camera with vertical field of view `fovy_deg`.
// MuJoCo's frustum is symmetric about the optical axis, which therefore passes through the
// centre of the viewport: window coordinate (W/2, H/2). GL pixel i covers [i, i+1) with its
// centre at i + 0.5, so with pixel centres at integer coordinates the principal point is
// (W/2 - 0.5, H/2 - 0.5); the row flip to top-down keeps cy there. Checked by the test
// Renderer.PointProjectsWhereItRenders.
PinholeIntrinsics IntrinsicsFromFovy(int width, int height, double fovy_deg) {
  PinholeIntrinsics k;
  k.width = width;
  k.height = height;
  k.fy = 0.5 * height / std::tan(0.5 * fovy_deg * M_PI / 180.0);
  k.fx = k.fy;
  k.cx = 0.5 * width - 0.5;
  k.cy = 0.5 * height - 0.5;
  return k;
}

// Camera poses at qpos0; checks that the pair is rectified: same orientation, right camera on
// the left camera's +x axis. Returns the baseline (m).
double RectifiedBaselineOrThrow(const mjModel* m, int left, int right) {
  DataPtr d(mj_makeData(m));
  mj_kinematics(m, d.get());
  mj_comPos(m, d.get());
  mj_camlight(m, d.get());
  const mjtNum* p_l = d->cam_xpos + 3 * left;
  const mjtNum* p_r = d->cam_xpos + 3 * right;
  const mjtNum* R_l = d->cam_xmat + 9 * left;  // columns: camera axes in world
  const mjtNum* R_r = d->cam_xmat + 9 * right;
  double delta_c[3] = {0, 0, 0};  // right camera position in the left camera frame (m)
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) delta_c[j] += R_l[3 * i + j] * (p_r[i] - p_l[i]);
  }
  double max_rot_diff = 0;
  for (int i = 0; i < 9; ++i) max_rot_diff = std::max(max_rot_diff, std::abs(R_l[i] - R_r[i]));
  const double baseline = std::sqrt(delta_c[0] * delta_c[0] + delta_c[1] * delta_c[1] + delta_c[2] * delta_c[2]);
  constexpr double kTolerance = 1e-5;  // (m) and (rotation matrix entries)
  if (baseline <= 0 || delta_c[0] <= 0 || std::abs(delta_c[1]) > kTolerance ||
      std::abs(delta_c[2]) > kTolerance || max_rot_diff > kTolerance) {
    std::ostringstream s;
    s << "stereo renderer: cam_left and cam_right are not a rectified pair (cam_right must sit at "
         "+baseline along cam_left's x axis with the same orientation); cam_right in cam_left's frame = ["
      << delta_c[0] << ", " << delta_c[1] << ", " << delta_c[2]
      << "] m, largest rotation matrix difference " << max_rot_diff;
    throw RunError(s.str());
  }
  return baseline;
}

// Switches the scene to ID-colour segmentation for one pass, with the effects that only cost
// time there (shadow maps, reflections, skybox, haze, fog) off; restores every flag when the
// pass ends, also when it throws.
class SegmentationFlags {
 public:
  explicit SegmentationFlags(mjvScene* scn) : scn_(scn) {
    std::copy(std::begin(scn_->flags), std::end(scn_->flags), saved_);
    for (int f : {mjRND_SHADOW, mjRND_REFLECTION, mjRND_SKYBOX, mjRND_HAZE, mjRND_FOG}) scn_->flags[f] = 0;
    scn_->flags[mjRND_SEGMENT] = 1;
    scn_->flags[mjRND_IDCOLOR] = 1;
  }
  ~SegmentationFlags() { std::copy(std::begin(saved_), std::end(saved_), scn_->flags); }
  SegmentationFlags(const SegmentationFlags&) = delete;
  SegmentationFlags& operator=(const SegmentationFlags&) = delete;

 private:
  mjvScene* scn_;
  mjtByte saved_[mjNRNDFLAG];  // the flags before the pass
};

}  // namespace

StereoRenderer::StereoRenderer(const mjModel* m, const RenderOptions& opt) : opt_(opt), ids_(m) {
  InstallMujocoHandlers();
  if (opt_.width <= 0 || opt_.height <= 0) {
    throw RunError("stereo renderer: image size must be positive, got " + std::to_string(opt_.width) + "x" +
                   std::to_string(opt_.height));
  }
  if (opt_.width > m->vis.global.offwidth || opt_.height > m->vis.global.offheight) {
    throw RunError("stereo renderer: requested " + std::to_string(opt_.width) + "x" +
                   std::to_string(opt_.height) + " px but the model's off-screen buffer is " +
                   std::to_string(m->vis.global.offwidth) + "x" + std::to_string(m->vis.global.offheight) +
                   " px; raise <visual><global offwidth=.. offheight=../>");
  }
  nbody_ = m->nbody;
  ngeom_ = m->ngeom;
  ncam_ = m->ncam;
  cam_left_ = CameraIdOrThrow(m, kLeftCamera);
  cam_right_ = CameraIdOrThrow(m, kRightCamera);
  const double fovy_deg = m->cam_fovy[cam_left_];
  if (std::abs(fovy_deg - m->cam_fovy[cam_right_]) > 1e-9) {
    throw RunError("stereo renderer: cam_left fovy " + std::to_string(fovy_deg) + " deg differs from cam_right fovy " +
                   std::to_string(m->cam_fovy[cam_right_]) + " deg");
  }
  intrinsics_ = IntrinsicsFromFovy(opt_.width, opt_.height, fovy_deg);
  baseline_m_ = RectifiedBaselineOrThrow(m, cam_left_, cam_right_);
  z_near_ = static_cast<float>(opt_.z_near_m > 0 ? opt_.z_near_m : m->vis.map.znear * m->stat.extent);
  z_far_ = static_cast<float>(opt_.z_far_m > 0 ? opt_.z_far_m : m->vis.map.zfar * m->stat.extent);
  if (!(z_near_ > 0 && z_far_ > z_near_)) {
    throw RunError("stereo renderer: clipping planes need 0 < near < far, got near " + std::to_string(z_near_) +
                   " m, far " + std::to_string(z_far_) + " m");
  }

  egl_ = EglContext::Create(opt_.egl_platform);

  mjv_defaultScene(&scn_);
  mjv_defaultOption(&vopt_);
  mjv_defaultCamera(&cam_);
  mjr_defaultContext(&con_);
  std::fill(std::begin(vopt_.sitegroup), std::end(vopt_.sitegroup), 0);  // sites are not scenery
  cam_.type = mjCAMERA_FIXED;
  viewport_ = mjrRect{0, 0, opt_.width, opt_.height};

  mjv_makeScene(m, &scn_, m->ngeom + kExtraSceneGeoms);
  try {
    // A shallow copy only to choose the off-screen multisampling; mjr_makeContext reads it.
    mjModel model_for_context = *m;
    if (opt_.multisamples >= 0) model_for_context.vis.quality.offsamples = opt_.multisamples;
    mjr_makeContext(&model_for_context, &con_, mjFONTSCALE_50);
    mjr_setBuffer(mjFB_OFFSCREEN, &con_);
    if (con_.currentBuffer != mjFB_OFFSCREEN) {
      throw RunError("stereo renderer: the off-screen framebuffer did not become current on " +
                     egl_->Description());
    }
    if (con_.offWidth < opt_.width || con_.offHeight < opt_.height) {
      throw RunError("stereo renderer: the off-screen framebuffer is only " + std::to_string(con_.offWidth) + "x" +
                     std::to_string(con_.offHeight) + " px");
    }
  } catch (...) {
    mjr_freeContext(&con_);
    mjv_freeScene(&scn_);
    throw;
  }
  ApplySceneFlags();

  const size_t pixels = static_cast<size_t>(opt_.width) * static_cast<size_t>(opt_.height);
  rgb_buf_.resize(3 * pixels);
  if (opt_.depth) depth_buf_.resize(pixels);
}

StereoRenderer::~StereoRenderer() {
  try {
    egl_->MakeCurrent();
    mjr_freeContext(&con_);
  } catch (...) {
    // The GL objects die with the context (destroyed next); nothing else can be done here.
  }
  mjv_freeScene(&scn_);
}

void StereoRenderer::ApplySceneFlags() {
  scn_.flags[mjRND_SHADOW] = opt_.shadows;
  scn_.flags[mjRND_REFLECTION] = opt_.reflections;
  scn_.flags[mjRND_SKYBOX] = opt_.skybox;
  scn_.flags[mjRND_HAZE] = opt_.haze;
  scn_.flags[mjRND_FOG] = 0;
  scn_.flags[mjRND_SEGMENT] = 0;
  scn_.flags[mjRND_IDCOLOR] = 0;
}

void StereoRenderer::RenderCamera(const mjModel* m, mjData* d, int cam_id, bool depth) {
  cam_.fixedcamid = cam_id;
  if (cam_id == cam_left_) {
    mjv_updateScene(m, d, &vopt_, nullptr, &cam_, mjCAT_ALL, &scn_);
    if (opt_.max_lights >= 0) scn_.nlight = std::min(scn_.nlight, opt_.max_lights);
  } else {
    mjv_updateCamera(m, d, &cam_, &scn_);  // the geoms of this instant are already in the scene
  }
  SetClipPlanes();
  mjr_render(viewport_, &scn_, &con_);
  mjr_readPixels(rgb_buf_.data(), depth ? depth_buf_.data() : nullptr, viewport_, &con_);
}

void StereoRenderer::SetClipPlanes() {
  const double tan_half_fovy = 0.5 * opt_.height / intrinsics_.fy;
  for (mjvGLCamera& c : scn_.camera) {
    // MuJoCo 2.2.2 sets a frustum symmetric about the axis: top = -bottom = near * tan(fovy/2).
    const double top = c.frustum_top / c.frustum_near, bottom = c.frustum_bottom / c.frustum_near;
    if (std::abs(top - tan_half_fovy) > 1e-5 || std::abs(bottom + tan_half_fovy) > 1e-5 || c.frustum_center != 0) {
      throw RunError("stereo renderer: MuJoCo's camera frustum (top " + std::to_string(top) + ", bottom " +
                     std::to_string(bottom) + ", centre " + std::to_string(c.frustum_center) +
                     " at unit distance) does not match the pinhole intrinsics (tan(fovy/2) = " +
                     std::to_string(tan_half_fovy) + ")");
    }
    c.frustum_bottom = static_cast<float>(z_near_ * bottom);
    c.frustum_top = static_cast<float>(z_near_ * top);
    c.frustum_near = z_near_;
    c.frustum_far = z_far_;
  }
}

namespace {

// Bottom-up RGB rows (GL) to a new top-down CV_8UC3 image.
cv::Mat FlipRgb(const std::vector<unsigned char>& rgb, int width, int height) {
  cv::Mat out(height, width, CV_8UC3);
  const size_t row_bytes = 3 * static_cast<size_t>(width);
  for (int r = 0; r < height; ++r) {
    std::copy_n(rgb.data() + row_bytes * static_cast<size_t>(height - 1 - r), row_bytes, out.ptr<unsigned char>(r));
  }
  return out;
}

}  // namespace

void StereoRenderer::Render(const mjModel* m, mjData* d, StereoFrame* out) {
  if (m->nbody != nbody_ || m->ngeom != ngeom_ || m->ncam != ncam_) {
    throw RunError("stereo renderer: Render got another model than the one it was made for");
  }
  egl_->MakeCurrent();
  mjr_setBuffer(mjFB_OFFSCREEN, &con_);
  const int w = opt_.width, h = opt_.height;

  out->t_ns = std::llround(d->time * 1e9);
  out->intrinsics = intrinsics_;
  out->baseline_m = baseline_m_;

  RenderCamera(m, d, cam_left_, opt_.depth);
  out->left_rgb = FlipRgb(rgb_buf_, w, h);
  if (opt_.depth) {
    // Window depth d in [0, 1] to distance along the optical axis; d = 1 (far plane, nothing
    // drawn) becomes 0 = no depth.
    const double near = z_near_, far = z_far_;
    const double k = 1.0 - near / far;
    out->left_depth_m = cv::Mat(h, w, CV_32F);
    for (int r = 0; r < h; ++r) {
      const float* src = depth_buf_.data() + static_cast<size_t>(w) * static_cast<size_t>(h - 1 - r);
      float* dst = out->left_depth_m.ptr<float>(r);
      for (int c = 0; c < w; ++c) {
        const double win = src[c];
        dst[c] = win >= 1.0 ? 0.0f : static_cast<float>(near / (1.0 - win * k));
      }
    }
  } else {
    out->left_depth_m = cv::Mat();
  }

  if (opt_.segmentation) {
    RenderSegmentation(m, out);
  } else {
    out->left_instance_id = cv::Mat();
    out->instances.clear();
  }

  RenderCamera(m, d, cam_right_, false);
  out->right_rgb = FlipRgb(rgb_buf_, w, h);
}

void StereoRenderer::RenderSegmentation(const mjModel* m, StereoFrame* out) {
  // The scene still holds the left camera's geoms. In IDCOLOR mode geom i is drawn with colour
  // segid + 1 (r + 256 g + 65536 b); 0 is the cleared background.
  seg_lut_.assign(static_cast<size_t>(scn_.ngeom) + 1, 0);
  for (int i = 0; i < scn_.ngeom; ++i) {
    const mjvGeom& g = scn_.geoms[i];
    if (g.segid < 0) continue;
    const size_t colour = static_cast<size_t>(g.segid) + 1;
    if (colour >= seg_lut_.size()) seg_lut_.resize(colour + 1, 0);
    seg_lut_[colour] = ids_.OfObject(m, g.objtype, g.objid);
  }
  {
    SegmentationFlags flags(&scn_);
    mjr_render(viewport_, &scn_, &con_);
    mjr_readPixels(rgb_buf_.data(), nullptr, viewport_, &con_);
  }

  const int w = opt_.width, h = opt_.height;
  out->left_instance_id = cv::Mat(h, w, CV_16U);
  std::vector<char> present(ids_.size(), 0);
  for (int r = 0; r < h; ++r) {
    const unsigned char* src = rgb_buf_.data() + 3 * static_cast<size_t>(w) * static_cast<size_t>(h - 1 - r);
    uint16_t* dst = out->left_instance_id.ptr<uint16_t>(r);
    for (int c = 0; c < w; ++c, src += 3) {
      const size_t colour = src[0] + (size_t{src[1]} << 8) + (size_t{src[2]} << 16);
      const uint16_t id = colour < seg_lut_.size() ? seg_lut_[colour] : 0;
      dst[c] = id;
      present[id] = 1;
    }
  }
  out->instances.clear();
  for (size_t id = 0; id < present.size(); ++id) {
    if (present[id]) out->instances.push_back(ids_.Instance(static_cast<uint16_t>(id)));
  }
}

}  // namespace viqu::sim
