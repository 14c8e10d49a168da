#include "runner/run_scenario.h"

#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <random>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "runner/foot_truth.h"
#include "runner/lo_run.h"
#include "runner/ordered_worker.h"
#include "runner/overlay_video.h"
#include "runner/progress.h"
#include "runner/robot_rig.h"
#include "runner/run_metrics.h"
#include "runner/scenario_settings.h"
#include "runner/scenario_warnings.h"
#include "runner/sensor_clock.h"
#include "runner/slam_run.h"
#include "common/atomic_file.h"
#include "common/errors.h"
#include "common/run_folder.h"
#include "common/stop_signal.h"
#include "scenario/scenario_loader.h"
#include "sim/camera_noise.h"
#include "sim/encoder_model.h"
#include "sim/euroc_recorder.h"
#include "sim/imu_model.h"
#include "sim/segmentation_model.h"
#include "sim/stereo_renderer.h"
#include "sim/torque_model.h"
#include "sim/touch_model.h"
#include "sim/trajectory_writer.h"
#include "sim/depth_quantisation.h"
#include "sim/tum_recorder.h"
#include "slam/core/dynamic_objects.h"
#include "slam/features/orb_extractor.h"
#include "slam/settings/slam_settings.h"

namespace viqu::runner {
namespace {

// Per-stream constants mixed into the scenario seed (docs/CONVENTIONS.md).
constexpr uint64_t kStreamImu = 0x1111'0000'0000'0001ULL;
constexpr uint64_t kStreamJoints = 0x2222'0000'0000'0002ULL;
constexpr uint64_t kStreamCamera = 0x3333'0000'0000'0003ULL;
constexpr uint64_t kStreamSegmentation = 0x4444'0000'0000'0004ULL;
constexpr uint64_t kStreamTouch = 0x5555'0000'0000'0005ULL;
constexpr uint64_t kStreamTorque = 0x6666'0000'0000'0006ULL;

constexpr double kFallTiltRad = 60.0 * M_PI / 180.0;  // trunk tilt that counts as a fall

// Camera frames that may wait for the estimator stage besides the one it works on: enough to
// smooth a keyframe's mapping time against the renderer, and a bound on the memory (about 3 MB a
// frame at 640x480). Not a tuning value: the outputs do not depend on it.
constexpr size_t kFramesQueued = 2;
// With robot.command.follow: estimate, the controller steers by the estimate of the camera frame
// this many frames before the last one rendered: a fixed delay (one frame period), so that the
// simulation never depends on how fast the estimator thread runs, which keeps the run
// deterministic while the renderer works ahead of the estimator. Part of the loop's definition.
constexpr int64_t kSteerDelayFrames = 1;

// The estimator stage's body pose after each camera frame, for steering; only the latest few are
// kept (frame k's is read while the stage may already write frame k + 1's).
class SteerPoses {
 public:
  void Put(int64_t frame, const Eigen::Isometry3d& T_w_body) {
    std::lock_guard<std::mutex> lock(mu_);
    slots_[frame % kSlots] = {frame, T_w_body};
  }
  Eigen::Isometry3d Get(int64_t frame) const {
    std::lock_guard<std::mutex> lock(mu_);
    const Slot& s = slots_[frame % kSlots];
    if (s.frame != frame) throw RunError("run loop: the estimate of frame " + std::to_string(frame) + " is not kept");
    return s.T_w_body;
  }

 private:
  static constexpr int64_t kSlots = 4;
  struct Slot {
    int64_t frame = -1;
    Eigen::Isometry3d T_w_body = Eigen::Isometry3d::Identity();
  };
  mutable std::mutex mu_;
  Slot slots_[kSlots];
};

// The sensor streams of one run: noise models and their clocks.
struct Sensors {
  explicit Sensors(const Scenario& s)
      : imu(s.sensors.imu, s.seed ^ kStreamImu),
        joints(s.sensors.joints, s.seed ^ kStreamJoints),
        segmentation(s.sensors.segmentation, s.seed ^ kStreamSegmentation),
        touch(s.sensors.touch, s.seed ^ kStreamTouch),
        torque(s.sensors.joints, s.seed ^ kStreamTorque),
        camera_rng(s.seed ^ kStreamCamera),
        imu_clock(s.sensors.imu.rate_hz),
        joint_clock(s.sensors.joints.rate_hz),
        camera_clock(s.sensors.camera.rate_hz) {}
  sim::ImuModel imu;
  sim::EncoderModel joints;
  sim::SegmentationModel segmentation;
  sim::TouchModel touch;
  sim::TorqueModel torque;
  std::mt19937_64 camera_rng;
  SensorClock imu_clock, joint_clock, camera_clock;
};

sim::EurocRig MakeEurocRig(const Scenario& s, const sim::World& w, const PinholeIntrinsics& k) {
  sim::EurocRig rig;
  rig.camera = s.sensors.camera;
  rig.intrinsics = k;
  rig.T_body_cam0 = w.T_body_cam(false);
  rig.T_body_cam1 = w.T_body_cam(true);
  rig.imu = s.sensors.imu;
  rig.joints = s.sensors.joints;
  rig.urdf_path = UrdfBesideMjcf(s.robot.model);
  return rig;
}

// ", ROBOT FELL at 2.20 s (trunk touched the ground)" for the summary line; "" when it did not.
std::string FellText(const RunMetrics& m) {
  if (!m.fell) return "";
  char text[128];
  std::snprintf(text, sizeof text, ", ROBOT FELL at %.2f s (%s)", m.fell_at_s, m.fell_how.c_str());
  return text;
}

}  // namespace

int RunScenario(const Scenario& s, const RunOptions& opt, RunObserver* observer) {
  const auto wall_start = std::chrono::steady_clock::now();
  // Only waypoints are followed on a pose; a velocity schedule is open loop whatever `follow` says
  // (ScenarioWarnings says so).
  const bool steer_by_estimate = s.robot.command.follow == "estimate" && !s.robot.command.waypoints.empty();
  if (steer_by_estimate && !opt.slam) {
    throw InputError(s.source_file + ": robot.command.follow: estimate needs the estimator; it cannot run with --no-slam");
  }
  // SLAM settings (scenario_settings.h); the resolved scenario records the values in effect.
  std::optional<slam::SlamSettings> settings;
  Scenario resolved = s;
  if (opt.slam) {
    settings = ScenarioSlamSettings(s);
    const slam::DynamicSettings& d = settings->dynamic;
    resolved.slam.mode = settings->mode;
    // (the other dynamic keys are written as the scenario gave them; slam_settings.yaml holds all)
    resolved.slam.dynamic = DynamicConfig{d.method, d.alpha, d.beta, d.gamma, d.th_d, d.window_s, d.window_n,
                                          s.slam.dynamic.more};
  }
  // Everything is checked: from here on the run writes its folder (common/run_folder.h).
  const std::string out_dir = opt.out_dir.empty() ? "runs/" + s.name : opt.out_dir;
  RunFolderWriter folder(out_dir, opt.force, opt.command_line,
                         {s.source_file, s.world, s.robot.model, UrdfBesideMjcf(s.robot.model), s.slam.config});
  const std::string& out = folder.path();
  WriteFileAtomic(out + "/scenario.yaml", ScenarioToYaml(resolved));

  RobotRig rig(s);
  sim::World& world = rig.world();
  const bool dynamic_stage = settings && slam::DynamicMethodOf(*settings) != slam::DynamicMethod::kNone;
  for (const std::string& w : ScenarioWarnings(s, dynamic_stage ? settings->dynamic.method : "",
                                               sim::FloorExtentOf(world.model()))) {
    std::fprintf(stderr, "viqu: warning: %s: %s\n", s.source_file.empty() ? s.name.c_str() : s.source_file.c_str(),
                 w.c_str());
  }
  sim::RenderOptions ropt;
  ropt.width = s.sensors.camera.width;
  ropt.height = s.sensors.camera.height;
  // Render only what this run consumes (each pass costs render time): the instance image for the
  // estimator (dynamic stage, dynamic.csv truth), a recording or the video; depth for a
  // recording, rgbd tracking (stereo tracking finds its own depth), or the detector model when it
  // grows masks: it grows the nearest instance first, by the median depth of its pixels
  // (sim/segmentation_model.h), so without depth the masks where two instances meet would differ
  // from those of the same run recorded.
  ropt.segmentation = s.sensors.camera.segmentation && (opt.slam || opt.record || opt.video);
  const bool masks_grow = ropt.segmentation && sim::SegmentationModel::GrowsMasks(s.sensors.segmentation);
  ropt.depth = s.sensors.camera.depth &&
               (opt.record || opt.record_tum || (opt.slam && settings->input == "rgbd") || masks_grow);
  sim::StereoRenderer renderer(world.model(), ropt);
  Sensors sensors(s);

  RunMetrics metrics;
  metrics.renderer = renderer.device_description();
  if (steer_by_estimate) metrics.steer_source = "estimate";
  // The map is anchored at the true first camera pose, so that the estimate and the ground
  // truth share a frame (ATE aligns them anyway), as the run's files print it (9 decimals), so
  // that a replay, which reads the anchor from those files, starts from the same numbers.
  std::unique_ptr<SlamRun> slam;
  if (opt.slam) {
    WriteFileAtomic(out + "/slam_settings.yaml", slam::SlamSettingsToYaml(*settings));
    const Eigen::Isometry3d T_w_c0 = ToIsometry(sim::AsReadBack(world.GroundTruth().T_w_cam));
    slam = std::make_unique<SlamRun>(*settings, out, T_w_c0);
  }
  // Leg odometry + IMU (mode full), anchored at the true first trunk pose likewise: one filter
  // alone (trajectory_lo.txt, lo.* metrics) and one fused with vision.
  std::unique_ptr<LoRun> lo;
  std::unique_ptr<lo::LegOdometry> fused_lo;
  std::unique_ptr<slam::VisualLegFusion> fusion;
  if (opt.slam && settings->mode == "full") {
    const Eigen::Isometry3d T_w_b0 = ToIsometry(sim::AsReadBack(world.GroundTruth().T_w_body));
    lo = std::make_unique<LoRun>(settings->lo, rig.kinematics(), out, world.time_ns(), T_w_b0, world.T_body_cam(false));
    fused_lo = std::make_unique<lo::LegOdometry>(settings->lo, rig.kinematics());
    fused_lo->Start(world.time_ns(), T_w_b0);
    lo->SetFused(fused_lo.get());
    fusion = std::make_unique<slam::VisualLegFusion>(fused_lo.get(), world.T_body_cam(false), settings->lo.fusion_min_inliers);
    slam->SetFusion(fusion.get());
  }
  eval::Trajectory gt_cam;
  // The feet's true contact and slip, every physics step (scored with the filter's, metrics only).
  std::unique_ptr<FootTruth> foot_truth;
  const auto step_foot_truth = [&foot_truth, &world](double dt_s) {
    std::array<Eigen::Vector3d, kNumLegs> sole;
    for (int i = 0; i < kNumLegs; ++i) sole[i] = world.FootSoleVelocityWorld(static_cast<Leg>(i));
    foot_truth->Step(world.time_ns(), dt_s, world.FootContacts(), sole);
  };
  if (lo) {
    foot_truth = std::make_unique<FootTruth>(s.scoring.slip_travel_m, s.scoring.contact_debounce_s);
    step_foot_truth(0.0);
  }

  std::unique_ptr<sim::EurocRecorder> recorder;
  if (opt.record) {
    recorder = std::make_unique<sim::EurocRecorder>(out + "/dataset", MakeEurocRig(s, world, renderer.intrinsics()));
  }
  std::unique_ptr<sim::TumRecorder> tum_recorder;
  if (opt.record_tum) {
    if (!s.sensors.camera.depth) throw InputError(s.source_file + ": --record-tum needs depth (sensors.camera.depth: true)");
    tum_recorder = std::make_unique<sim::TumRecorder>(out + "/dataset_tum", renderer.intrinsics());
  }
  std::unique_ptr<OverlayVideo> video;
  if (opt.video) {
    video = std::make_unique<OverlayVideo>(out + "/video.mp4", s.sensors.camera.rate_hz, ropt.width, ropt.height);
  }
  // The overlays (video, viewer) show every feature's fate; recording it changes no output.
  if (slam && (video || observer)) slam->SetRecordFeatures(true);
  sim::TrajectoryWriter gt_out(out + "/trajectory_gt.txt");

  ProgressLine progress(s.duration_s);
  const int64_t end_ns = std::llround(s.duration_s * 1e9);
  Eigen::Vector3d last_p = world.GroundTruth().T_w_body.p_w_x;
  StereoFrame frame;
  const Eigen::Isometry3d T_cam_body = world.T_body_cam(false).inverse();
  // The contact readings the filters get (lo.contact; "estimated" needs none), decided once.
  const bool lo_touch = lo && settings->lo.contact == "touch";
  const bool lo_schedule = lo && settings->lo.contact == "schedule";
  // The estimator stage: everything that consumes the measurements (leg odometry, SLAM, the
  // overlay video) runs on its own thread, one camera frame's worth of measurements per task, in
  // the order the simulation produced them, while this thread steps the physics and renders the
  // next frame (runner/ordered_worker.h). --sequential runs the tasks inline instead; the outputs
  // are the same bytes either way.
  // An observer looks at the simulation and the estimator together: the stage runs inline then.
  OrderedWorker estimator(kFramesQueued, opt.sequential || observer != nullptr);
  bool observer_stop = false;     // the observer asked to end the run (a viewer closed)
  ObservedFrame observed;         // the last frame the observer saw
  std::vector<std::function<void()>> measured;  // the estimator's share since the last camera frame
  std::atomic<const char*> track_note{""};      // the last frame's tracking status, for the progress line
  // With robot.command.follow: estimate the robot steers by the estimate of the camera frame before
  // the last one (kSteerDelayFrames): the body pose in the fused filter (mode full) or from the
  // visual pose, as the estimator stage had it after that frame. Before that estimate exists it
  // steers by the pose the estimator is anchored at.
  SteerPoses steer_poses;
  ctrl::Pose2 steer_pose = Pose2Of(ToIsometry(world.GroundTruth().T_w_body));
  int64_t frame_index = 0;
  int stop_signal = 0;
  const bool imu_mean = s.sensors.imu.sampling == "mean";  // sensors.imu.sampling, decided once
  const bool torque_by_mean = s.sensors.joints.torque_sampling == "mean";
  while (true) {
    const int64_t t_ns = world.time_ns();

    if (sensors.imu_clock.Due(t_ns)) {
      const sim::World::ImuMean mean = world.TakeImuMean();
      const ImuSample imu = sensors.imu.Measure(t_ns, imu_mean ? mean.accel_i : world.TrueAccel(),
                                                imu_mean ? mean.gyro_i : world.TrueGyro());
      if (recorder) recorder->AddImu(imu);
      if (lo) {
        measured.push_back([&lo, &fused_lo, imu] {
          lo->AddImu(imu);
          fused_lo->AddImu(imu);
        });
      }
    }
    if (sensors.joint_clock.Due(t_ns)) {
      JointState js = sensors.joints.Measure(t_ns, world.JointPositions(), world.JointVelocities(),
                                             world.FootContacts());
      // The servos' torque, from its own seeded stream (the encoders' draws do not change).
      const std::array<double, kNumJoints> torque_mean = world.TakeJointTorqueMean();
      js.torque_nm = sensors.torque.Measure(torque_by_mean ? torque_mean : world.JointTorques());
      js.has_torque = true;
      if (recorder) recorder->AddJoints(js);
      // The controller publishes its planned stance with every encoder reading; the touch
      // sensors are read with the encoders (their own seeded stream: reading them changes no other).
      const ContactReading planned{t_ns, rig.gait().planned_stance()};
      std::optional<ContactReading> touch;
      if (recorder || lo_touch) touch = sensors.touch.Measure(t_ns, world.FootNormalForces());
      if (recorder) recorder->AddContact(t_ns, touch->stance, planned.stance);
      if (lo) {
        std::optional<ContactReading> contact;
        if (lo_touch || lo_schedule) contact = lo_touch ? *touch : planned;
        LoTruth truth;
        truth.contact = foot_truth->contact();
        truth.normal_force_n = world.FootNormalForces();
        for (int i = 0; i < kNumLegs; ++i) truth.travel_m[i] = foot_truth->travel_m(i);
        const GroundTruthState gt = world.GroundTruth();
        truth.p_w_body = gt.T_w_body.p_w_x;
        truth.q_w_body = gt.T_w_body.q_w_x;
        truth.w_body = world.TrueGyro();
        truth.vel_w_body = gt.vel_w_body;
        truth.gyro_bias_i = sensors.imu.gyro_bias();
        for (int i = 0; i < kNumLegs; ++i) truth.sole_speed_mps[i] = world.FootSoleVelocityWorld(static_cast<Leg>(i)).norm();
        const int64_t period_ns = sensors.joint_clock.period_ns();
        measured.push_back([&lo, &fused_lo, contact, js, truth, period_ns] {
          if (contact) {
            lo->AddContact(*contact);
            fused_lo->AddContact(*contact);
          }
          fused_lo->AddJoints(js);
          lo->AddJoints(js, period_ns, truth);
        });
      }
    }
    if (sensors.camera_clock.Due(t_ns)) {
      const auto r0 = std::chrono::steady_clock::now();
      renderer.Render(world.model(), world.data(), &frame);
      metrics.render_ms.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - r0).count());
      // The camera's pixel noise is drawn here, in the order of the other draws, and added on the
      // estimator's thread (with the recorders' images), off this one, which paces the run
      // (2 x 2.6 ms a frame): the same bytes as adding it here. A camera outage gives black
      // images, after the noise draws (so that the seeded streams of the rest of the run do not
      // change).
      const sim::PixelNoiseDraw noise_left = sim::DrawPixelNoise(s.sensors.camera.noise_std, &sensors.camera_rng);
      const sim::PixelNoiseDraw noise_right = sim::DrawPixelNoise(s.sensors.camera.noise_std, &sensors.camera_rng);
      bool dark = false;
      for (const Vec2& d : s.sensors.camera.dropouts) {
        dark = dark || (t_ns >= std::llround(d[0] * 1e9) && t_ns < std::llround(d[1] * 1e9));
      }
      const auto finish_images = [noise_left, noise_right, dark](StereoFrame* f) {
        sim::ApplyPixelNoise(noise_left, &f->left_rgb);
        sim::ApplyPixelNoise(noise_right, &f->right_rgb);
        if (dark) {
          f->left_rgb.setTo(cv::Scalar::all(0));
          f->right_rgb.setTo(cv::Scalar::all(0));
        }
      };
      // The simulator's truth about the obstacles, from the ideal instance image, before the
      // detector model changes it.
      std::vector<ObjectTruth> truth;
      if (slam || recorder) truth = ObjectTruthOf(frame, world.obstacles(), t_ns * 1e-9);
      if (recorder) recorder->AddObjectTruth(t_ns, truth);
      if (!frame.left_instance_id.empty()) sensors.segmentation.Apply(&frame);
      // Depth as a depth camera delivers it: quantised to TUM's 1/5000 m, so that a recorded
      // TUM dataset replays exactly as the live run saw it.
      // The steps go to the recorders as they are (one conversion a frame).
      const cv::Mat depth_steps = sim::QuantiseDepth(&frame.left_depth_m, sim::TumRecorder::kDepthScale);
      const GroundTruthState gt = world.GroundTruth();
      gt_out.Add(gt.T_w_cam);
      gt_cam.push_back(gt.T_w_cam);
      metrics.path_length_m += (gt.T_w_body.p_w_x - last_p).head<2>().norm();
      last_p = gt.T_w_body.p_w_x;
      ++metrics.frames;
      if (recorder) recorder->AddGroundTruth(gt);
      if (tum_recorder) tum_recorder->AddGroundTruth(gt);
      // The frame goes to the estimator stage with the measurements before it; the renderer
      // makes new images for the next frame.
      const int64_t index = frame_index++;
      estimator.Post([&, index, t_ns, measured = std::move(measured), frame = std::move(frame),
                      truth = std::move(truth), p_w_cam = gt.T_w_cam.p_w_x, finish_images, depth_steps]() mutable {
        finish_images(&frame);
        // The recorders take their images here, the rest of their streams on the simulation
        // thread: AddFrame shares no state with their other Add calls (sim/euroc_recorder.h).
        if (recorder) recorder->AddFrame(frame, depth_steps);
        if (tum_recorder) tum_recorder->AddFrame(frame, depth_steps);
        for (const std::function<void()>& m : measured) m();
        if (lo) lo->AddFrame(t_ns);
        std::optional<slam::TrackResult> track;
        if (slam) {
          track = slam->Track(frame, &truth);
          metrics.track_ms.push_back(track->track_ms);
          track_note = slam::TrackStatusName(track->status);
        }
        if (video) {
          const double error_m = track ? (track->T_w_c.translation() - p_w_cam).norm() : -1;
          video->Add(frame, track ? &*track : nullptr, error_m);
        }
        if (steer_by_estimate) steer_poses.Put(index, fused_lo ? fused_lo->T_w_body() : track->T_w_c * T_cam_body);
        if (observer) {  // inline: this is the simulation thread, and the world is at t_ns
          observed = {index, t_ns * 1e-9, s.duration_s, &world, &frame, track ? &*track : nullptr, slam.get(), &gt_cam,
                      lo ? &lo->estimate() : nullptr};
          observer_stop = !observer->OnFrame(observed);
          observed.frame = nullptr;
          observed.track = nullptr;
        }
      });
      measured = {};
      frame = StereoFrame();
      if (steer_by_estimate && index >= kSteerDelayFrames) {
        estimator.WaitUntil(static_cast<uint64_t>(index - kSteerDelayFrames));
        steer_pose = Pose2Of(steer_poses.Get(index - kSteerDelayFrames));
      }
    }
    if (!metrics.fell && (world.TrunkTiltRad() > kFallTiltRad || world.TrunkTouchesGround())) {
      metrics.fell = true;
      metrics.fell_at_s = t_ns * 1e-9;
      char how[64];
      std::snprintf(how, sizeof how, "trunk tilted %.0f deg", world.TrunkTiltRad() * 180 / M_PI);
      metrics.fell_how = world.TrunkTiltRad() > kFallTiltRad ? how : "trunk touched the ground";
    }
    if (t_ns >= end_ns || (metrics.fell && !s.robot.allow_fall)) break;
    // A stop request (SIGINT, SIGTERM) ends the run here, between two physics steps: every
    // sample and frame so far is processed, and the outputs are finished as at the end.
    if ((stop_signal = StopSignal()) != 0 || observer_stop) break;
    rig.Step(steer_by_estimate ? steer_pose : rig.TruePose2());
    if (foot_truth) step_foot_truth(s.physics_dt_s);
    progress.SetNote(track_note.load());
    progress.Update(world.data()->time);
  }
  // The measurements after the last frame, then wait for the stage to finish everything.
  if (!measured.empty()) {
    estimator.Post([measured = std::move(measured)] {
      for (const std::function<void()>& m : measured) m();
    });
  }
  estimator.Finish();
  progress.Finish();

  gt_out.Close();
  if (recorder) recorder->Finish();
  if (tum_recorder) tum_recorder->Finish();
  if (video) video->Finish();
  metrics.sim_time_s = world.data()->time;
  metrics.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  JsonWriter json;
  AddRunMetrics(s, metrics, &json);
  SlamSummary summary;
  if (slam) summary = slam->Finish(gt_cam, metrics.path_length_m, &json);
  LoSummary lo_summary;
  if (lo) lo_summary = lo->Finish(gt_cam, metrics.path_length_m, foot_truth->Finish(world.time_ns()), s.scoring, &json);
  WriteFileAtomic(out + "/metrics.json", json.ToString());

  const int exit_code = metrics.fell && !s.robot.allow_fall ? 1 : 0;
  if (stop_signal != 0 || observer_stop) {
    // Ended early, by a stop signal or by the viewer: the outputs so far, marked incomplete.
    char reason[128];
    std::snprintf(reason, sizeof(reason), "%s at simulated time %.3f s of %.3f s",
                  stop_signal != 0 ? SignalName(stop_signal) : "the viewer closed", metrics.sim_time_s, s.duration_s);
    folder.Interrupted(reason);
    std::fprintf(stderr, "viqu: run stopped (%s); %s holds the outputs so far, marked incomplete (%s)\n", reason,
                 folder.final_path().c_str(), kRunIncompleteMarker);
    if (stop_signal != 0) return ExitCodeForSignal(stop_signal);
    observer->OnRunEnd(observed);
    return 0;
  }
  folder.Complete(exit_code);
  std::printf("viqu run %s: %.1f s simulated in %.1f s (real-time factor %.2fx), path %.2f m, %d frames, "
              "render %.1f ms median%s\n",
              s.name.c_str(), metrics.sim_time_s, metrics.wall_time_s, metrics.sim_time_s / metrics.wall_time_s,
              metrics.path_length_m, metrics.frames, Median(metrics.render_ms), FellText(metrics).c_str());
  if (slam) std::printf("SLAM: %s\n", SlamSummaryLine(summary).c_str());
  if (lo) std::printf("%s\n", LoSummaryLine(lo_summary).c_str());
  std::printf("outputs: %s\n", OutputsLine(folder.final_path()).c_str());
  if (observer) observer->OnRunEnd(observed);
  return exit_code;
}

}  // namespace viqu::runner
