// Tests of the off-screen stereo renderer (sim/stereo_renderer.h) and the instance table
// (sim/segmentation_ids.h) on inline scenes: depth against MuJoCo ray casts, segmentation of
// obstacles, projection of known points (the half-pixel convention) and stereo disparity.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/errors.h"
#include "sim/mujoco_handles.h"
#include "sim/segmentation_ids.h"
#include "sim/stereo_renderer.h"

namespace viqu::sim {
namespace {

constexpr int kWidth = 640, kHeight = 480;

// A textured floor and back wall, a stereo rig 0.3 m above the floor looking along world +x
// (cam_right at +0.04 m along the left camera's x = world -y), and one object per category.
// Small red emissive balls mark known 3D points.
const char* const kSceneXml = R"(
<mujoco model="render_test">
  <visual><global offwidth="640" offheight="480"/></visual>
  <asset>
    <texture name="grid" type="2d" builtin="checker" rgb1=".2 .3 .4" rgb2=".8 .8 .8" width="256" height="256"/>
    <material name="grid" texture="grid" texrepeat="8 8"/>
    <texture name="wall" type="2d" builtin="checker" rgb1=".6 .2 .1" rgb2=".9 .9 .7" width="128" height="128"
             mark="random" random="0.1" markrgb="0 0 0"/>
    <material name="wall" texture="wall" texrepeat="6 3"/>
    <material name="glow" rgba="1 0 0 1" emission="1"/>
  </asset>
  <worldbody>
    <light pos="0 0 3" dir="0 0 -1"/>
    <geom name="floor" type="plane" size="6 6 0.1" material="grid"/>
    <geom name="back_wall" type="box" pos="4 0 1" size="0.05 3 1" material="wall"/>
    <body name="rig" pos="0 0 0.3">
      <camera name="cam_left" pos="0 0.02 0" xyaxes="0 -1 0 0 0 1" fovy="70"/>
      <camera name="cam_right" pos="0 -0.02 0" xyaxes="0 -1 0 0 0 1" fovy="70"/>
    </body>
    <body name="box:crate" mocap="true" pos="1.2 0.35 0.1">
      <geom type="box" size="0.1 0.1 0.1" rgba="0.7 0.5 0.2 1"/>
    </body>
    <body name="person:bob" mocap="true" pos="2.0 -0.5 0.55">
      <geom type="capsule" size="0.12 0.15" rgba="0.2 0.6 0.3 1"/>
    </body>
    <body name="person:bob/leg_l" mocap="true" pos="2.0 -0.5 0.15">
      <geom type="capsule" size="0.05 0.12" rgba="0.2 0.2 0.6 1"/>
    </body>
    <body name="trunk" pos="1.0 -0.35 0.05">
      <geom type="box" size="0.1 0.04 0.025" rgba="0.3 0.3 0.3 1"/>
      <body name="rat/leg" pos="0 0 -0.02">
        <geom type="sphere" size="0.02" rgba="0.9 0.9 0.9 1"/>
      </body>
    </body>
    <body name="ball:centre" pos="1.5 0.02 0.3"><geom type="sphere" size="0.03" material="glow"/></body>
    <body name="ball:upper_left" pos="1.5 0.55 0.62"><geom type="sphere" size="0.03" material="glow"/></body>
    <body name="ball:lower_right" pos="1.2 -0.6 0.12"><geom type="sphere" size="0.03" material="glow"/></body>
    <body name="ball:far" pos="3.0 -1.2 0.9"><geom type="sphere" size="0.04" material="glow"/></body>
  </worldbody>
</mujoco>
)";

std::vector<std::string> AllWarnings() { return TakeMujocoWarnings(); }

// Position of world point `p_w` in the OpenCV optical frame of MuJoCo camera `cam`
// (x right, y down, z forward): MuJoCo's camera frame rotated by pi about x.
Eigen::Vector3d InOpticalFrame(const mjData* d, int cam, const Eigen::Vector3d& p_w) {
  const Eigen::Map<const Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor>> R_w_cmj(d->cam_xmat + 9 * cam);
  const Eigen::Map<const Eigen::Vector3d> p_w_c(d->cam_xpos + 3 * cam);
  const Eigen::Vector3d p_cmj = R_w_cmj.transpose() * (p_w - p_w_c);
  return Eigen::Vector3d(p_cmj.x(), -p_cmj.y(), -p_cmj.z());
}

// Image of the centre of a sphere's silhouette. A sphere (centre X,Y,Z, radius r) projects to an
// ellipse centred at f * (X, Y) * Z / (Z^2 - r^2) from the principal point: slightly outward of
// the projected centre, which this accounts for.
Eigen::Vector2d SphereImageCentre(const PinholeIntrinsics& k, const Eigen::Vector3d& c, double r) {
  const double s = c.z() / (c.z() * c.z() - r * r);
  return Eigen::Vector2d(k.fx * c.x() * s + k.cx, k.fy * c.y() * s + k.cy);
}

// Centroid of the non-zero pixels of a mask (pixel centres at integer coordinates).
Eigen::Vector2d Centroid(const cv::Mat& mask, int* count) {
  const cv::Moments mo = cv::moments(mask, true);
  *count = static_cast<int>(mo.m00);
  return Eigen::Vector2d(mo.m10 / mo.m00, mo.m01 / mo.m00);
}

// Pixels that show the glowing red balls in an RGB image.
cv::Mat RedMask(const cv::Mat& rgb) {
  cv::Mat mask;
  cv::inRange(rgb, cv::Scalar(150, 0, 0), cv::Scalar(255, 60, 60), mask);
  return mask;
}

class RendererTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    model_ = LoadModelString(kSceneXml, "render_test scene").release();
    data_ = mj_makeData(model_);
    mj_forward(model_, data_);
    RenderOptions opt;
    opt.width = kWidth;
    opt.height = kHeight;
    renderer_ = new StereoRenderer(model_, opt);
  }
  static void TearDownTestSuite() {
    delete renderer_;
    mj_deleteData(data_);
    mj_deleteModel(model_);
  }
  void TearDown() override {
    const std::vector<std::string> warnings = AllWarnings();
    for (const std::string& w : warnings) ADD_FAILURE() << "MuJoCo warning: " << w;
  }

  StereoFrame Render() {
    StereoFrame f;
    renderer_->Render(model_, data_, &f);
    return f;
  }
  int Camera(const char* name) const { return mj_name2id(model_, mjOBJ_CAMERA, name); }
  int Body(const char* name) const { return mj_name2id(model_, mjOBJ_BODY, name); }
  Eigen::Vector3d BodyPos(const char* name) const {
    return Eigen::Map<const Eigen::Vector3d>(data_->xpos + 3 * Body(name));
  }

  static mjModel* model_;
  static mjData* data_;
  static StereoRenderer* renderer_;
};
mjModel* RendererTest::model_ = nullptr;
mjData* RendererTest::data_ = nullptr;
StereoRenderer* RendererTest::renderer_ = nullptr;

TEST_F(RendererTest, FrameHasEveryImageWithTheRightTypeAndTime) {
  data_->time = 1.25;
  const StereoFrame f = Render();
  data_->time = 0;
  EXPECT_EQ(f.t_ns, 1250000000);
  EXPECT_EQ(f.left_rgb.type(), CV_8UC3);
  EXPECT_EQ(f.right_rgb.type(), CV_8UC3);
  EXPECT_EQ(f.left_depth_m.type(), CV_32F);
  EXPECT_EQ(f.left_instance_id.type(), CV_16U);
  for (const cv::Mat* img : {&f.left_rgb, &f.right_rgb, &f.left_depth_m, &f.left_instance_id}) {
    EXPECT_EQ(img->cols, kWidth);
    EXPECT_EQ(img->rows, kHeight);
  }
  EXPECT_NEAR(f.baseline_m, 0.04, 1e-12);
  const double fy = 0.5 * kHeight / std::tan(0.5 * 70.0 * M_PI / 180.0);
  EXPECT_NEAR(f.intrinsics.fy, fy, 1e-9);
  EXPECT_NEAR(f.intrinsics.fx, fy, 1e-9);
  EXPECT_EQ(f.intrinsics.width, kWidth);
  EXPECT_EQ(f.intrinsics.height, kHeight);

  // Right side up: the sky (nothing drawn, black, no depth) is at the top, the floor at the bottom.
  EXPECT_EQ(f.left_depth_m.at<float>(2, kWidth / 2), 0.0f);
  EXPECT_EQ(f.left_rgb.at<cv::Vec3b>(2, kWidth / 2), cv::Vec3b(0, 0, 0));
  EXPECT_GT(f.left_depth_m.at<float>(kHeight - 3, kWidth / 2), 0.0f);
  EXPECT_GT(cv::norm(f.left_rgb.at<cv::Vec3b>(kHeight - 3, kWidth / 2)), 50.0);

  // A look at the images: left, right and instance ids side by side.
  cv::Mat ids8, ids_rgb, row, bgr;
  f.left_instance_id.convertTo(ids8, CV_8U, 40);
  cv::cvtColor(ids8, ids_rgb, cv::COLOR_GRAY2RGB);
  cv::hconcat(std::vector<cv::Mat>{f.left_rgb, f.right_rgb, ids_rgb}, row);
  cv::cvtColor(row, bgr, cv::COLOR_RGB2BGR);
  EXPECT_TRUE(cv::imwrite(std::string(VIQU_BINARY_DIR) + "/render_check.png", bgr));
}

// Depth at pixel centres equals the optical-axis depth of the point a MuJoCo ray through the
// same pixel centre hits. The ray direction (x, y, 1) in the optical frame makes mj_ray's
// distance the depth itself. Pixels on object edges (a neighbouring ray hits another geom) are
// skipped, since a half-pixel there decides which surface is seen.
TEST_F(RendererTest, DepthMatchesRayCast) {
  const StereoFrame f = Render();
  const PinholeIntrinsics& k = f.intrinsics;
  const int cam = Camera("cam_left");
  const Eigen::Map<const Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor>> R_w_cmj(data_->cam_xmat + 9 * cam);
  auto cast = [&](double u, double v, int* geom) {
    const Eigen::Vector3d dir_opt((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0);
    const Eigen::Vector3d dir_w = R_w_cmj * Eigen::Vector3d(dir_opt.x(), -dir_opt.y(), -dir_opt.z());
    return mj_ray(model_, data_, data_->cam_xpos + 3 * cam, dir_w.data(), nullptr, 1, -1, geom);
  };
  int compared = 0, misses = 0, edges = 0;
  double worst = 0;
  for (int v = 4; v < kHeight - 4; v += 12) {
    for (int u = 4; u < kWidth - 4; u += 12) {
      int geom = -1;
      const double z_ray = cast(u, v, &geom);
      bool edge = false;
      for (const auto& [du, dv] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        int g = -1;
        cast(u + du, v + dv, &g);
        edge |= (g != geom);
      }
      if (edge) {
        ++edges;
        continue;
      }
      const float z_img = f.left_depth_m.at<float>(v, u);
      if (z_ray < 0) {
        ++misses;
        EXPECT_EQ(z_img, 0.0f) << "pixel (" << u << ", " << v << ") sees nothing along the ray";
        continue;
      }
      ++compared;
      const double rel = std::abs(z_img - z_ray) / z_ray;
      worst = std::max(worst, rel);
      EXPECT_LT(rel, 0.005) << "pixel (" << u << ", " << v << "): depth " << z_img << " m, ray " << z_ray
                            << " m, geom " << geom;
    }
  }
  std::printf("depth vs mj_ray: %d pixels compared (worst relative error %.2e), %d see nothing, %d edges skipped\n",
              compared, worst, misses, edges);
  EXPECT_GT(compared, 1500);
  EXPECT_GT(misses, 100);
}

// The projected centre of every obstacle carries its instance; a person of two bodies is one
// instance; the robot subtree is category robot; world geoms are background.
TEST_F(RendererTest, SegmentationCoversObstacles) {
  const SegmentationIds& ids = renderer_->segmentation_ids();
  const uint16_t crate = ids.OfBody(Body("box:crate"));
  const uint16_t bob = ids.OfBody(Body("person:bob"));
  const uint16_t robot = ids.OfBody(Body("trunk"));
  ASSERT_NE(crate, 0);
  EXPECT_EQ(ids.OfBody(Body("person:bob/leg_l")), bob);
  EXPECT_EQ(ids.OfBody(Body("rat/leg")), robot);
  EXPECT_EQ(ids.OfBody(Body("rig")), 0);
  EXPECT_EQ(ids.Instance(crate).category, Category::kBox);
  EXPECT_EQ(ids.Instance(crate).name, "crate");
  EXPECT_EQ(ids.Instance(bob).category, Category::kPerson);
  EXPECT_EQ(ids.Instance(bob).name, "bob");
  EXPECT_EQ(ids.Instance(robot).category, Category::kRobot);

  const int cam = Camera("cam_left");
  auto id_at = [&](const StereoFrame& f, const Eigen::Vector3d& p_w) {
    const Eigen::Vector3d p = InOpticalFrame(data_, cam, p_w);
    const PinholeIntrinsics& k = f.intrinsics;
    const int u = static_cast<int>(std::lround(k.fx * p.x() / p.z() + k.cx));
    const int v = static_cast<int>(std::lround(k.fy * p.y() / p.z() + k.cy));
    EXPECT_TRUE(u >= 0 && u < kWidth && v >= 0 && v < kHeight) << "point projects outside the image";
    return f.left_instance_id.at<uint16_t>(std::clamp(v, 0, kHeight - 1), std::clamp(u, 0, kWidth - 1));
  };

  const StereoFrame f = Render();
  EXPECT_EQ(id_at(f, BodyPos("box:crate")), crate);
  EXPECT_EQ(id_at(f, BodyPos("person:bob")), bob);
  EXPECT_EQ(id_at(f, BodyPos("person:bob/leg_l")), bob);
  EXPECT_EQ(id_at(f, BodyPos("trunk")), robot);
  EXPECT_EQ(id_at(f, Eigen::Vector3d(1.5, -0.1, 0.0)), 0) << "the floor is background";
  EXPECT_EQ(id_at(f, Eigen::Vector3d(3.95, 0.3, 1.0)), 0) << "the wall is background";

  // The instance list describes exactly the ids present.
  std::vector<uint16_t> listed;
  for (const SegmentInstance& in : f.instances) {
    listed.push_back(in.id);
    EXPECT_GT(cv::countNonZero(f.left_instance_id == in.id), 0) << in.name;
    EXPECT_EQ(in.category, ids.Instance(in.id).category);
  }
  for (uint16_t id : {uint16_t{0}, crate, bob, robot}) {
    EXPECT_NE(std::find(listed.begin(), listed.end(), id), listed.end()) << "id " << id << " not listed";
  }
  // Every labelled pixel has depth (segmentation and depth agree on what is drawn).
  const cv::Mat labelled = f.left_instance_id > 0;
  const cv::Mat no_depth = f.left_depth_m <= 0;
  EXPECT_EQ(cv::countNonZero(labelled & no_depth), 0);

  // The mask follows the obstacle when the script moves it.
  const int mocap = model_->body_mocapid[Body("box:crate")];
  const Eigen::Vector3d old_pos(data_->mocap_pos + 3 * mocap);
  const Eigen::Vector3d new_pos(1.6, -0.05, 0.1);
  Eigen::Map<Eigen::Vector3d>(data_->mocap_pos + 3 * mocap) = new_pos;
  mj_forward(model_, data_);
  const StereoFrame moved = Render();
  Eigen::Map<Eigen::Vector3d>(data_->mocap_pos + 3 * mocap) = old_pos;
  mj_forward(model_, data_);
  EXPECT_EQ(id_at(moved, new_pos), crate);
  EXPECT_EQ(id_at(moved, old_pos), 0) << "the crate's old place shows the floor";
}

// A point at a known 3D position renders at the pixel the intrinsics predict: the centroid of
// each ball's instance mask against the ellipse centre of the ball's projection. This decides the
// half-pixel convention: with cx = W/2 - 0.5, cy = H/2 - 0.5 the error is a few hundredths of
// a pixel; cx = W/2 would put every ball 0.5 px off.
TEST_F(RendererTest, PointProjectsWhereItRenders) {
  const StereoFrame f = Render();
  const SegmentationIds& ids = renderer_->segmentation_ids();
  const int cam = Camera("cam_left");
  Eigen::Vector2d mean_error = Eigen::Vector2d::Zero();
  int n = 0;
  for (const char* ball : {"ball:centre", "ball:upper_left", "ball:lower_right", "ball:far"}) {
    const int body = Body(ball);
    const double radius = model_->geom_size[3 * model_->body_geomadr[body]];
    const Eigen::Vector3d p = InOpticalFrame(data_, cam, BodyPos(ball));
    const Eigen::Vector2d predicted = SphereImageCentre(f.intrinsics, p, radius);
    int pixels = 0;
    const Eigen::Vector2d seen = Centroid(f.left_instance_id == ids.OfBody(body), &pixels);
    ASSERT_GT(pixels, 30) << ball;
    const Eigen::Vector2d err = seen - predicted;
    std::printf("%-18s predicted (%.3f, %.3f) rendered (%.3f, %.3f) error (%+.3f, %+.3f) px over %d px\n", ball,
                predicted.x(), predicted.y(), seen.x(), seen.y(), err.x(), err.y(), pixels);
    EXPECT_LT(err.norm(), 0.15) << ball;
    mean_error += err;
    ++n;

    // The RGB image agrees with the instance image.
    int red_pixels = 0;
    cv::Mat red = RedMask(f.left_rgb);
    cv::Mat near_ball = cv::Mat::zeros(red.size(), CV_8U);
    cv::circle(near_ball, cv::Point(static_cast<int>(seen.x()), static_cast<int>(seen.y())), 20, 255, -1);
    const Eigen::Vector2d seen_rgb = Centroid(red & near_ball, &red_pixels);
    EXPECT_LT((seen_rgb - predicted).norm(), 0.25) << ball << " in the RGB image";
  }
  mean_error /= n;
  EXPECT_LT(mean_error.norm(), 0.08) << "systematic offset: the principal point is off";
}

// The right image shows a point shifted left by the disparity fx * b / z (right camera at
// +baseline along the left camera's x axis).
TEST_F(RendererTest, RightImageShiftedByDisparity) {
  const StereoFrame f = Render();
  const PinholeIntrinsics& k = f.intrinsics;
  const int left = Camera("cam_left"), right = Camera("cam_right");
  for (const char* ball : {"ball:centre", "ball:upper_left", "ball:far"}) {
    const int body = Body(ball);
    const double radius = model_->geom_size[3 * model_->body_geomadr[body]];
    const Eigen::Vector3d p_l = InOpticalFrame(data_, left, BodyPos(ball));
    const Eigen::Vector3d p_r = InOpticalFrame(data_, right, BodyPos(ball));
    EXPECT_NEAR(p_r.x(), p_l.x() - f.baseline_m, 1e-9) << "right camera at +baseline along left x";
    const Eigen::Vector2d predicted_l = SphereImageCentre(k, p_l, radius);
    const Eigen::Vector2d predicted_r = SphereImageCentre(k, p_r, radius);

    cv::Mat near_l = cv::Mat::zeros(kHeight, kWidth, CV_8U), near_r = near_l.clone();
    cv::circle(near_l, cv::Point(static_cast<int>(predicted_l.x()), static_cast<int>(predicted_l.y())), 20, 255, -1);
    cv::circle(near_r, cv::Point(static_cast<int>(predicted_r.x()), static_cast<int>(predicted_r.y())), 20, 255, -1);
    int n_l = 0, n_r = 0;
    const Eigen::Vector2d seen_l = Centroid(RedMask(f.left_rgb) & near_l, &n_l);
    const Eigen::Vector2d seen_r = Centroid(RedMask(f.right_rgb) & near_r, &n_r);
    ASSERT_GT(n_l, 30) << ball;
    ASSERT_GT(n_r, 30) << ball;
    const double disparity = seen_l.x() - seen_r.x();
    const double expected = k.fx * f.baseline_m / p_l.z();
    std::printf("%-16s z %.3f m: disparity %.3f px, fx*b/z %.3f px, rows %.3f vs %.3f\n", ball, p_l.z(), disparity,
                expected, seen_l.y(), seen_r.y());
    EXPECT_NEAR(disparity, expected, 0.25) << ball;
    EXPECT_NEAR(seen_l.y(), seen_r.y(), 0.25) << ball << ": rectified pair, same row";
  }
}

// Two renderers in one process (one EGL display, two contexts) take turns; each makes its own
// context current and both give the same images. Destroying one leaves the other working.
TEST_F(RendererTest, TwoRenderersTakeTurns) {
  RenderOptions opt;
  opt.width = kWidth;
  opt.height = kHeight;
  auto second = std::make_unique<StereoRenderer>(model_, opt);
  StereoFrame a, b;
  renderer_->Render(model_, data_, &a);
  second->Render(model_, data_, &b);
  EXPECT_EQ(cv::norm(a.left_rgb, b.left_rgb, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.right_rgb, b.right_rgb, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.left_instance_id, b.left_instance_id, cv::NORM_INF), 0.0);
  second.reset();
  const StereoFrame c = Render();
  EXPECT_EQ(cv::norm(a.left_rgb, c.left_rgb, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.left_depth_m, c.left_depth_m, cv::NORM_INF), 0.0);
}

// A camera 7 cm above the floor in a large room (extent ~ 20 m) sees the floor 0.1 m ahead at
// its bottom row: the near plane must not clip it, and the depth there is h * fy / (v - cy).
TEST(RendererNearTest, LowCameraSeesTheFloorAtItsFeet) {
  const std::string xml = R"(<mujoco><visual><global offwidth="320" offheight="240"/></visual><worldbody>
      <geom type="plane" size="10 10 0.1" rgba=".5 .5 .5 1"/>
      <geom type="box" pos="10 0 1" size="0.1 10 1" rgba=".7 .7 .7 1"/>
      <camera name="cam_left" pos="0 0.02 0.07" xyaxes="0 -1 0 0 0 1" fovy="70"/>
      <camera name="cam_right" pos="0 -0.02 0.07" xyaxes="0 -1 0 0 0 1" fovy="70"/>
      </worldbody></mujoco>)";
  ModelPtr m = LoadModelString(xml, "low camera");
  DataPtr d(mj_makeData(m.get()));
  mj_forward(m.get(), d.get());
  RenderOptions opt;
  opt.width = 320;
  opt.height = 240;
  opt.segmentation = false;
  StereoRenderer r(m.get(), opt);
  StereoFrame f;
  r.Render(m.get(), d.get(), &f);
  EXPECT_TRUE(f.left_instance_id.empty());
  EXPECT_TRUE(f.instances.empty());
  const PinholeIntrinsics& k = f.intrinsics;
  for (int v : {opt.height - 1, opt.height - 20, opt.height / 2 + 20}) {
    const double expected = 0.07 * k.fy / (v - k.cy);
    EXPECT_NEAR(f.left_depth_m.at<float>(v, opt.width / 2), expected, 0.005 * expected) << "row " << v;
  }
  EXPECT_TRUE(TakeMujocoWarnings().empty());
}

// Both EGL platforms give a working context on this machine's Mesa; the renderer on the
// surfaceless fallback draws the same scene as on the device platform.
TEST(EglContextTest, DevicePlatformAndSurfacelessFallbackBothWork) {
  const auto device = EglContext::Create(EglContext::Platform::kDevice);
  EXPECT_NE(device->Description().find("device platform"), std::string::npos) << device->Description();
  const auto surfaceless = EglContext::Create(EglContext::Platform::kSurfaceless);
  EXPECT_NE(surfaceless->Description().find("surfaceless"), std::string::npos) << surfaceless->Description();
  std::printf("EGL: %s | %s\n", device->Description().c_str(), surfaceless->Description().c_str());

  ModelPtr m = LoadModelString(kSceneXml, "render_test scene");
  DataPtr d(mj_makeData(m.get()));
  mj_forward(m.get(), d.get());
  RenderOptions opt;
  StereoFrame frames[2];
  int i = 0;
  for (auto platform : {EglContext::Platform::kDevice, EglContext::Platform::kSurfaceless}) {
    opt.egl_platform = platform;
    StereoRenderer r(m.get(), opt);
    r.Render(m.get(), d.get(), &frames[i++]);
  }
  EXPECT_EQ(cv::norm(frames[0].left_instance_id, frames[1].left_instance_id, cv::NORM_INF), 0.0);
  EXPECT_LT(cv::norm(frames[0].left_rgb, frames[1].left_rgb, cv::NORM_L1) / frames[0].left_rgb.total(), 1.0);
  EXPECT_TRUE(TakeMujocoWarnings().empty());
}

TEST(RendererSetupTest, RejectsMissingCameraAndOversizedImages) {
  const std::string no_right = R"(<mujoco><worldbody>
      <camera name="cam_left" pos="0 0 1"/><geom type="sphere" size="0.1"/></worldbody></mujoco>)";
  ModelPtr m = LoadModelString(no_right, "no_right");
  try {
    StereoRenderer r(m.get(), RenderOptions{});
    ADD_FAILURE() << "a model without cam_right was accepted";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("cam_right"), std::string::npos) << e.what();
  }

  const std::string small = R"(<mujoco><visual><global offwidth="320" offheight="240"/></visual><worldbody>
      <camera name="cam_left" pos="0 0 1"/><camera name="cam_right" pos="0.04 0 1"/></worldbody></mujoco>)";
  m = LoadModelString(small, "small");
  try {
    StereoRenderer r(m.get(), RenderOptions{});
    ADD_FAILURE() << "640x480 was accepted with a 320x240 off-screen buffer";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("320x240"), std::string::npos) << e.what();
  }

  const std::string toed_in = R"(<mujoco><worldbody>
      <camera name="cam_left" pos="0 0 1"/><camera name="cam_right" pos="0.04 0 1" euler="0 5 0"/>
      </worldbody></mujoco>)";
  m = LoadModelString(toed_in, "toed_in");
  RenderOptions opt;
  opt.width = 320;
  opt.height = 240;
  EXPECT_THROW(StereoRenderer(m.get(), opt), RunError);
  EXPECT_TRUE(TakeMujocoWarnings().empty());
}

TEST(SegmentationIdsTest, RejectsUnknownCategory) {
  const std::string xml = R"(<mujoco><worldbody>
      <body name="persn:bob"><geom type="sphere" size="0.1"/></body></worldbody></mujoco>)";
  ModelPtr m = LoadModelString(xml, "typo");
  EXPECT_THROW(SegmentationIds ids(m.get()), InputError);
}

TEST(SegmentationIdsTest, IdsFollowBodyOrderAndGroupParts) {
  const std::string xml = R"(<mujoco><worldbody>
      <geom type="plane" size="1 1 1"/>
      <body name="table"><geom type="box" size="0.1 0.1 0.1"/></body>
      <body name="ball:b1" mocap="true"><geom type="sphere" size="0.1"/></body>
      <body name="person:ann/leg_r" mocap="true"><geom type="sphere" size="0.1"/></body>
      <body name="furniture:shelf"><geom type="box" size="0.1 0.1 0.1"/>
        <body name="shelf_board"><geom type="box" size="0.1 0.1 0.01"/></body></body>
      <body name="person:ann" mocap="true"><geom type="sphere" size="0.1"/></body>
      </worldbody></mujoco>)";
  ModelPtr m = LoadModelString(xml, "ids");
  const SegmentationIds ids(m.get());
  auto of = [&](const char* body) { return ids.OfBody(mj_name2id(m.get(), mjOBJ_BODY, body)); };
  EXPECT_EQ(ids.size(), 4u);
  EXPECT_EQ(of("table"), 0);
  EXPECT_EQ(of("ball:b1"), 1);
  EXPECT_EQ(of("person:ann/leg_r"), 2);
  EXPECT_EQ(of("person:ann"), 2);
  EXPECT_EQ(of("furniture:shelf"), 3);
  EXPECT_EQ(of("shelf_board"), 3);
  EXPECT_EQ(ids.Instance(2).name, "ann");
  EXPECT_EQ(ids.Instance(3).category, Category::kFurniture);
  EXPECT_EQ(ids.OfObject(m.get(), mjOBJ_GEOM, 0), 0) << "world geom";
  EXPECT_EQ(ids.OfObject(m.get(), mjOBJ_UNKNOWN, -1), 0) << "decor";
}

}  // namespace
}  // namespace viqu::sim
