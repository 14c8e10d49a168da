#include "apps/slam_command.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <algorithm>
#include <limits>
#include <optional>

#include "runner/slam_run.h"
#include "common/atomic_file.h"
#include "common/errors.h"
#include "common/json_writer.h"
#include "common/run_folder.h"
#include "common/stop_signal.h"
#include "sim/trajectory_writer.h"
#include "kinematics/leg_kinematics.h"
#include "slam/features/orb_extractor.h"
#include "slam/fusion/gyro_motion_prior.h"
#include "slam/fusion/visual_leg_fusion.h"
#include "slam/io/object_truth_csv.h"
#include "slam/io/open_dataset.h"
#include "slam/io/proprioception_reader.h"
#include "slam/lo/leg_odometry.h"
#include "slam/settings/slam_settings.h"

namespace viqu::app {
namespace {

std::string DefaultOutDir(const std::string& dataset_dir) {
  std::filesystem::path p(dataset_dir);
  if (p.filename().empty()) p = p.parent_path();
  return "runs/slam-" + p.filename().string();
}


// The ground-truth pose nearest to t_ns within 0.02 s (as the evaluation associates), if any.
const StampedPose* NearestPose(const eval::Trajectory& gt, int64_t t_ns) {
  const StampedPose* best = nullptr;
  int64_t best_d = 20'000'000;
  for (const StampedPose& p : gt) {
    const int64_t d = std::llabs(p.t_ns - t_ns);
    if (d < best_d) {
      best_d = d;
      best = &p;
    }
  }
  return best;
}

double PathLength(const eval::Trajectory& gt) {
  double len = 0;
  for (size_t i = 1; i < gt.size(); ++i) len += (gt[i].p_w_x - gt[i - 1].p_w_x).norm();
  return len;
}

// Feeds a recording's IMU, contact and encoder samples to the filter in the live run's order:
// every sample up to a frame's time before the frame; at one stamp the IMU, then the contact
// reading, then the encoders.
class ProprioceptionFeed {
 public:
  ProprioceptionFeed(const io::Proprioception& p, const std::string& contact_source, lo::LegOdometry* lo)
      : p_(p), contacts_(contact_source == "schedule" ? &p.planned : contact_source == "touch" ? &p.touch : nullptr), lo_(lo) {}

  void Until(int64_t t_ns) {
    constexpr int64_t kNone = std::numeric_limits<int64_t>::max();
    while (true) {
      const int64_t ti = i_ < p_.imu.size() ? p_.imu[i_].t_ns : kNone;
      const int64_t tc = contacts_ && c_ < contacts_->size() ? (*contacts_)[c_].t_ns : kNone;
      const int64_t tj = j_ < p_.joints.size() ? p_.joints[j_].t_ns : kNone;
      const int64_t t = std::min({ti, tc, tj});
      if (t == kNone || t > t_ns) return;
      if (ti == t) {
        lo_->AddImu(p_.imu[i_++]);
      } else if (tc == t) {
        lo_->AddContact((*contacts_)[c_++]);
      } else {
        lo_->AddJoints(p_.joints[j_++]);
      }
    }
  }

 private:
  const io::Proprioception& p_;
  const std::vector<ContactReading>* contacts_;
  lo::LegOdometry* lo_;
  size_t i_ = 0, c_ = 0, j_ = 0;
};

}  // namespace

int RunSlamCommand(const SlamArgs& args, const std::string& command_line) {
  const auto wall_start = std::chrono::steady_clock::now();
  const io::DatasetFormat format = io::ParseDatasetFormat(args.format);
  // Settings first: a mistyped --set is reported before the dataset is scanned. A key in the
  // scenario's form (slam.dynamic.method, as viqu run --set takes it) is the same setting; messages
  // name it as typed.
  std::vector<std::string> sets, origins;
  for (const std::string& set : args.sets) {
    const bool scenario_form = set.rfind("slam.", 0) == 0;
    sets.push_back(scenario_form ? set.substr(5) : set);
    origins.push_back(scenario_form ? "--set " + set : "");
  }
  slam::SlamSettings settings =
      slam::LoadSlamSettings(args.config.empty() ? slam::DefaultSlamSettingsPath() : args.config, sets, origins);
  std::unique_ptr<io::DatasetReader> reader = io::OpenDataset(args.dataset_dir, format, args.masks_dir, args.camera);
  reader->AllowSkippingBadFrames(args.skip_bad_frames);
  const PinholeIntrinsics& k = reader->intrinsics();
  std::printf("viqu slam: camera %s: fx %g fy %g cx %g cy %g, %dx%d\n", reader->calibration_source().c_str(), k.fx, k.fy,
              k.cx, k.cy, k.width, k.height);
  if (format == io::DatasetFormat::kTum && settings.input != "rgbd") {
    std::fprintf(stderr, "viqu: note: TUM RGB-D has no right image; tracking in rgbd mode\n");
    settings.input = "rgbd";
  }
  if (settings.input == "rgbd" && !reader->HasDepth()) {
    throw InputError(args.dataset_dir + ": settings ask for rgbd input but the dataset has no depth images");
  }
  const std::string pyramid = slam::PyramidProblem(settings.orb.scale_factor, settings.orb.num_levels,
                                                   reader->intrinsics().width, reader->intrinsics().height);
  if (!pyramid.empty()) throw InputError(settings.pyramid_where + ": " + pyramid);
  if (settings.input == "stereo" && reader->baseline_m() <= 0) {
    throw InputError(args.dataset_dir + ": settings ask for stereo input but the dataset has no right camera");
  }

  const std::string out_dir = args.out_dir.empty() ? DefaultOutDir(args.dataset_dir) : args.out_dir;
  // The output folder is replaced as a whole: it must not hold anything the replay reads, nor lie
  // inside it.
  RunFolderWriter folder(out_dir, args.force, command_line, {args.dataset_dir, args.masks_dir, args.camera, args.config});
  const std::string& out = folder.path();
  char camera_line[512];
  std::snprintf(camera_line, sizeof camera_line, "# camera calibration: %s (fx %g, fy %g, cx %g, cy %g, %dx%d)\n",
                reader->calibration_source().c_str(), k.fx, k.fy, k.cx, k.cy, k.width, k.height);
  WriteFileAtomic(out + "/slam_settings.yaml", camera_line + slam::SlamSettingsToYaml(settings));

  const eval::Trajectory gt = reader->ground_truth().value_or(eval::Trajectory{});
  // Mode full on a viqu recording with its proprioceptive streams: leg odometry + IMU fused with
  // vision as in the live run (anchored at the trunk's first ground-truth pose, as live).
  std::optional<io::Proprioception> proprio;
  std::optional<kin::LegKinematics> kin;
  std::unique_ptr<lo::LegOdometry> fused_lo;
  std::unique_ptr<slam::VisualLegFusion> fusion;
  std::unique_ptr<ProprioceptionFeed> feed;
  if (settings.mode == "full" && format == io::DatasetFormat::kViqu) proprio = io::ReadViquProprioception(args.dataset_dir);
  // Mode full on a dataset with an IMU but no leg encoders (EuRoC): the gyro's rotation prior.
  const io::InertialStream* imu = settings.mode == "full" && !proprio ? reader->inertial() : nullptr;
  std::unique_ptr<slam::GyroMotionPrior> gyro;
  if (imu) {
    gyro = std::make_unique<slam::GyroMotionPrior>(lo::AttitudeOptionsOf(settings.lo), imu->T_imu_cam);
    std::fprintf(stderr, "viqu: note: mode full with %s: the gyro gives the motion prior (no leg odometry)\n",
                 imu->source.c_str());
  } else if (settings.mode == "full" && !proprio) {
    std::fprintf(stderr, "viqu: note: no imu0/joints0/contact0/robot.urdf in the dataset: mode full runs on vision alone\n");
  }
  size_t next_imu = 0;
  if (proprio) {
    kin = kin::LegKinematics::FromUrdfFile(proprio->urdf_path);
    fused_lo = std::make_unique<lo::LegOdometry>(settings.lo, *kin);
    const StampedPose start = proprio->body_at_start.value_or(StampedPose{});
    fused_lo->Start(start.t_ns, ToIsometry(start));
    fusion = std::make_unique<slam::VisualLegFusion>(fused_lo.get(), proprio->T_body_cam0, settings.lo.fusion_min_inliers);
    feed = std::make_unique<ProprioceptionFeed>(*proprio, settings.lo.contact, fused_lo.get());
  }
  // The objects' truth a viqu recording kept (objects0): the replay's dynamic-object decisions
  // are scored as the live run's were.
  std::optional<io::ObjectTruthStream> objects;
  if (format == io::DatasetFormat::kViqu) objects = io::ReadViquObjectTruth(args.dataset_dir);
  const std::vector<ObjectTruth> no_objects;
  std::unique_ptr<runner::SlamRun> run;
  StereoFrame frame;
  int64_t first_t = 0, last_t = 0;
  int frames = 0;
  int stop_signal = 0;
  while ((stop_signal = StopSignal()) == 0 && reader->Next(&frame)) {
    if (!run) {
      // The map is anchored at the ground-truth pose of the first frame when there is one, as
      // the live run anchors it, so that both give the same trajectory.
      const StampedPose* p0 = NearestPose(gt, frame.t_ns);
      run = std::make_unique<runner::SlamRun>(settings, out, p0 ? ToIsometry(*p0) : Eigen::Isometry3d::Identity());
      if (fusion) run->SetFusion(fusion.get());
      if (gyro) run->SetGyroPrior(gyro.get());
      first_t = frame.t_ns;
    }
    if (feed) feed->Until(frame.t_ns);
    while (gyro && next_imu < imu->samples.size() && imu->samples[next_imu].t_ns <= frame.t_ns) {
      gyro->AddImu(imu->samples[next_imu++]);
    }
    const std::vector<ObjectTruth>* truth = nullptr;
    if (objects) {
      const auto at = objects->find(frame.t_ns);
      truth = at == objects->end() ? &no_objects : &at->second;
    }
    const slam::TrackResult r = run->Track(frame, truth);
    last_t = frame.t_ns;
    ++frames;
    if (r.status == slam::TrackStatus::kLost && frames > 1) {
      std::fprintf(stderr, "viqu: frame %d (t=%s s): tracking lost\n", frames, sim::FormatSeconds(r.t_ns).c_str());
    }
  }
  if (!run && stop_signal == 0) throw InputError(args.dataset_dir + ": the dataset has no readable frames");
  if (!run) return ExitCodeForSignal(stop_signal);  // stopped before the first frame: nothing to keep

  JsonWriter json;
  json.Set("dataset", args.dataset_dir);
  json.Set("format", io::DatasetFormatName(format));
  json.Set("camera.calibration", reader->calibration_source());
  json.Set("camera.fx", k.fx);
  json.Set("camera.fy", k.fy);
  json.Set("camera.cx", k.cx);
  json.Set("camera.cy", k.cy);
  json.Set("camera.width", k.width);
  json.Set("camera.height", k.height);
  json.Set("camera.frames_skipped", reader->frames_skipped());
  if (!args.masks_dir.empty()) json.Set("masks", args.masks_dir);
  json.Set("sim_time_s", (last_t - first_t) * 1e-9);
  const double path = reader->path_length_m().value_or(PathLength(gt));
  if (!gt.empty()) {
    json.Set("path_length_m", path);
    sim::TrajectoryWriter gt_out(out + "/trajectory_gt.txt");
    for (const StampedPose& p : gt) gt_out.Add(p);
    gt_out.Close();
  }
  const runner::SlamSummary summary = run->Finish(gt, path, &json);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  json.Set("timing.wall_time_s", wall);
  WriteFileAtomic(out + "/metrics.json", json.ToString());
  if (stop_signal != 0) {
    const std::string reason = std::string(SignalName(stop_signal)) + " after " + std::to_string(frames) + " frames";
    folder.Interrupted(reason);
    std::fprintf(stderr, "viqu: replay stopped by %s; %s holds the outputs so far, marked incomplete (%s)\n",
                 reason.c_str(), folder.final_path().c_str(), kRunIncompleteMarker);
    return ExitCodeForSignal(stop_signal);
  }
  folder.Complete(0);
  if (!summary.ate_unavailable.empty()) std::fprintf(stderr, "viqu: note: no ATE: %s\n", summary.ate_unavailable.c_str());
  if (reader->frames_skipped() > 0) {
    std::fprintf(stderr, "viqu: note: %d unreadable frame(s) skipped (--skip-bad-frames; metrics.json camera.frames_skipped)\n",
                 reader->frames_skipped());
  }
  const std::string skipped =
      reader->frames_skipped() > 0 ? ", " + std::to_string(reader->frames_skipped()) + " unreadable skipped" : "";
  std::printf("viqu slam %s (%s): %d frames%s in %.1f s\n", args.dataset_dir.c_str(), io::DatasetFormatName(format),
              frames, skipped.c_str(), wall);
  std::printf("SLAM: %s\n", runner::SlamSummaryLine(summary).c_str());
  std::printf("outputs: %s\n", OutputsLine(folder.final_path()).c_str());
  return 0;
}

}  // namespace viqu::app
