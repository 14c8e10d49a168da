#include "sim/euroc_recorder.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <utility>
#include <vector>

#include "common/atomic_file.h"
#include "common/errors.h"
#include "sim/depth_quantisation.h"
#include "sim/tum_recorder.h"

namespace viqu::sim {
namespace {

namespace fs = std::filesystem;

const char* const kJointNames[kNumJoints] = {"FL_hip", "FL_knee", "FR_hip", "FR_knee",
                                             "BL_hip", "BL_knee", "BR_hip", "BR_knee"};
const char* const kFootNames[kNumLegs] = {"FL", "FR", "BL", "BR"};
// depth0 PNG unit: 1/5000 m, the steps that the live run quantises its depth to (TUM's depth
// scale, runner/run_scenario.cc), so that a recorded depth image replays bit for bit and an rgbd
// replay of the recording tracks exactly as the live run did. The range, 13.1 m, is the live
// depth's own: beyond it there is no depth live either.
constexpr double kDepthStepsPerM = TumRecorder::kDepthScale;
constexpr double kDepthUnitM = 1.0 / kDepthStepsPerM;

std::string Fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), format, v);
  return buf;
}

// The shortest of %.15g, %.16g, %.17g that reads back as exactly `v` (17 digits always do):
// "0.1" stays "0.1", and a replay gets the very double of the run.
std::string Exact(double v) {
  char buf[64];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof(buf), "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

void MakeDirs(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw RunError("cannot create " + dir.string() + ": " + ec.message());
}

// "T_BS:" block of a EuRoC sensor.yaml: the sensor frame S in the body frame B, row-major.
std::string TransformYaml(const Eigen::Isometry3d& T_B_S) {
  const Eigen::Matrix4d m = T_B_S.matrix();
  std::string s = "T_BS:\n  cols: 4\n  rows: 4\n  data: [";
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      s += Exact(m(r, c));
      if (r < 3 || c < 3) s += c == 3 ? ",\n         " : ", ";
    }
  }
  return s + "]\n";
}

std::string CameraYaml(const std::string& comment, const Eigen::Isometry3d& T_B_S, const EurocRig& rig,
                       const std::string& extra) {
  const PinholeIntrinsics& k = rig.intrinsics;
  std::string s = "# General sensor definitions.\nsensor_type: camera\ncomment: " + comment + "\n\n";
  s += "# Sensor extrinsics wrt. the body-frame.\n" + TransformYaml(T_B_S) + "\n";
  s += "# Camera specific definitions.\n";
  s += "rate_hz: " + Fmt("%.9g", rig.camera.rate_hz) + "\n";
  s += "resolution: [" + std::to_string(k.width) + ", " + std::to_string(k.height) + "]\n";
  s += "camera_model: pinhole\n";
  // Exact digits: a replay must project with the very intrinsics and extrinsics of the live run.
  s += "intrinsics: [" + Exact(k.fx) + ", " + Exact(k.fy) + ", " + Exact(k.cx) + ", " + Exact(k.cy) +
       "]  # fu, fv, cu, cv\n";
  s += "distortion_model: radial-tangential\n";
  s += "distortion_coefficients: [0, 0, 0, 0]\n";
  return s + extra;
}

std::string RowStamp(int64_t t_ns) { return std::to_string(t_ns); }

}  // namespace

EurocRecorder::EurocRecorder(const std::string& dataset_dir, const EurocRig& rig)
    : final_dir_(fs::path(dataset_dir).lexically_normal().string()),
      partial_dir_(final_dir_ + ".partial"),
      mav0_(partial_dir_ + "/mav0"),
      rig_(rig) {
  std::error_code ec;
  fs::remove_all(partial_dir_, ec);
  if (ec) throw RunError("cannot remove stale " + partial_dir_ + ": " + ec.message());
  MakeDirs(mav0_ + "/cam0/data");
  MakeDirs(mav0_ + "/cam1/data");
  if (rig_.camera.depth) MakeDirs(mav0_ + "/depth0/data");
  if (rig_.camera.segmentation) {
    MakeDirs(mav0_ + "/seg0/data");
    MakeDirs(mav0_ + "/objects0");
  }
  MakeDirs(mav0_ + "/imu0");
  MakeDirs(mav0_ + "/joints0");
  MakeDirs(mav0_ + "/contact0");
  MakeDirs(mav0_ + "/state_groundtruth_estimate0");

  const std::string image_header = "#timestamp [ns],filename\n";
  cam0_ = OpenCsv("cam0", image_header);
  cam1_ = OpenCsv("cam1", image_header);
  if (rig_.camera.depth) depth0_ = OpenCsv("depth0", image_header);
  if (rig_.camera.segmentation) {
    seg0_ = OpenCsv("seg0", image_header);
    seg0_frames_.file = std::make_unique<AtomicOutputFile>(mav0_ + "/seg0/frame_instances.csv");
    seg0_frames_.file->Write("#timestamp [ns],id,category,name\n");
    objects0_ = OpenCsv("objects0", "#timestamp [ns],visible_px,truly_moving,category,name\n");
  }
  imu0_ = OpenCsv("imu0",
                  "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
                  "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n");
  std::string joints_header = "#timestamp [ns]";
  for (const char* j : kJointNames) joints_header += std::string(",") + j + " [rad]";
  for (const char* j : kJointNames) joints_header += std::string(",") + j + "_vel [rad s^-1]";
  for (const char* f : kFootNames) joints_header += std::string(",") + f + "_contact [0/1]";
  for (const char* j : kJointNames) joints_header += std::string(",") + j + "_torque [N m]";
  joints0_ = OpenCsv("joints0", joints_header + "\n");
  std::string contact_header = "#timestamp [ns]";
  for (const char* f : kFootNames) contact_header += std::string(",") + f + "_touch [0/1]";
  for (const char* f : kFootNames) contact_header += std::string(",") + f + "_planned [0/1]";
  contact0_ = OpenCsv("contact0", contact_header + "\n");
  if (!rig_.urdf_path.empty()) {
    std::error_code ec;
    fs::copy_file(rig_.urdf_path, mav0_ + "/robot.urdf", fs::copy_options::overwrite_existing, ec);
    if (ec) throw RunError("cannot copy " + rig_.urdf_path + " into the recording: " + ec.message());
  }
  gt0_ = OpenCsv("state_groundtruth_estimate0",
                 "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], "
                 "q_RS_z [], v_RS_R_x [m s^-1], v_RS_R_y [m s^-1], v_RS_R_z [m s^-1], "
                 "b_w_RS_S_x [rad s^-1], b_w_RS_S_y [rad s^-1], b_w_RS_S_z [rad s^-1], "
                 "b_a_RS_S_x [m s^-2], b_a_RS_S_y [m s^-2], b_a_RS_S_z [m s^-2]\n");
}

EurocRecorder::~EurocRecorder() {
  if (finished_) return;
  writer_.reset();  // stop writing images into the folder that is about to go
  // Close (and delete) the temporary CSV files first, then the whole partial folder.
  for (CsvStream* s : {&cam0_, &cam1_, &depth0_, &seg0_, &seg0_frames_, &objects0_, &imu0_, &joints0_, &contact0_, &gt0_}) s->file.reset();
  std::error_code ec;
  fs::remove_all(partial_dir_, ec);
}

EurocRecorder::CsvStream EurocRecorder::OpenCsv(const std::string& folder, const std::string& header) const {
  CsvStream s;
  s.file = std::make_unique<AtomicOutputFile>(mav0_ + "/" + folder + "/data.csv");
  s.file->Write(header);
  return s;
}

void EurocRecorder::CheckStamp(CsvStream* s, int64_t t_ns, const char* what) const {
  if (finished_) throw RunError(std::string("EurocRecorder: ") + what + " added after Finish()");
  if (t_ns <= s->last_t_ns) {
    throw RunError(std::string("EurocRecorder: ") + what + " timestamp " + std::to_string(t_ns) +
                   " ns does not follow " + std::to_string(s->last_t_ns) + " ns");
  }
  s->last_t_ns = t_ns;
}

void EurocRecorder::WriteImage(const std::string& folder, CsvStream* csv, int64_t t_ns, cv::Mat image,
                               PngContent content) {
  CheckStamp(csv, t_ns, folder.c_str());
  const std::string name = RowStamp(t_ns) + ".png";
  const std::string path = mav0_ + "/" + folder + "/data/" + name;
  writer_->Push(path, std::move(image), content);  // encoded on the queue's thread
  csv->file->Write(RowStamp(t_ns) + "," + name + "\n");
}

void EurocRecorder::AddFrame(const StereoFrame& frame, const cv::Mat& depth_steps) {
  for (const cv::Mat* m : {&frame.left_rgb, &frame.right_rgb}) {
    if (m->type() != CV_8UC3) throw RunError("EurocRecorder: stereo images must be CV_8UC3 (RGB)");
  }
  // The frame's images are copied for the queue (the caller goes on with its buffers); the depth
  // steps below are a new image already, or the caller's, which it does not modify.
  WriteImage("cam0", &cam0_, frame.t_ns, frame.left_rgb.clone(), PngContent::kPhoto);
  WriteImage("cam1", &cam1_, frame.t_ns, frame.right_rgb.clone(), PngContent::kPhoto);

  if (rig_.camera.depth && !frame.left_depth_m.empty()) {
    WriteImage("depth0", &depth0_, frame.t_ns,
               DepthStepsToWrite(frame.left_depth_m, depth_steps, kDepthStepsPerM, "EurocRecorder"), PngContent::kFlat);
  }
  if (rig_.camera.segmentation && !frame.left_instance_id.empty()) {
    if (frame.left_instance_id.type() != CV_16U) throw RunError("EurocRecorder: instance ids must be CV_16U");
    WriteImage("seg0", &seg0_, frame.t_ns, frame.left_instance_id.clone(), PngContent::kFlat);
    std::string rows;
    for (const SegmentInstance& inst : frame.instances) {
      rows += RowStamp(frame.t_ns) + "," + std::to_string(inst.id) + "," + CategoryName(inst.category) + "," +
              inst.name + "\n";
      SeenInstance& seen = instances_[inst.id];
      if (seen.frames.empty()) seen.name = inst.name;
      ++seen.frames[inst.category];
      seen.first_ns.emplace(inst.category, frame.t_ns);
    }
    seg0_frames_.file->Write(rows);
  }
}

void EurocRecorder::AddObjectTruth(int64_t t_ns, const std::vector<ObjectTruth>& objects) {
  if (!objects0_.file) return;
  CheckStamp(&objects0_, t_ns, "object truth");
  std::string rows;
  for (const ObjectTruth& o : objects) {
    rows += RowStamp(t_ns) + "," + std::to_string(o.visible_px) + "," + (o.moving ? "1" : "0") + "," +
            CategoryName(o.category) + "," + o.name + "\n";
  }
  objects0_.file->Write(rows);
}

void EurocRecorder::AddImu(const ImuSample& s) {
  CheckStamp(&imu0_, s.t_ns, "imu0");
  std::string row = RowStamp(s.t_ns);
  for (int i = 0; i < 3; ++i) row += "," + Exact(s.gyro_i[i]);
  for (int i = 0; i < 3; ++i) row += "," + Exact(s.accel_i[i]);
  imu0_.file->Write(row + "\n");
}

void EurocRecorder::AddJoints(const JointState& j) {
  CheckStamp(&joints0_, j.t_ns, "joints0");
  std::string row = RowStamp(j.t_ns);
  for (double q : j.position_rad) row += "," + Exact(q);
  for (double v : j.velocity_rad_s) row += "," + Exact(v);
  for (bool c : j.contact) row += c ? ",1" : ",0";
  for (double t : j.torque_nm) row += "," + Exact(t);
  joints0_.file->Write(row + "\n");
}

void EurocRecorder::AddContact(int64_t t_ns, const std::array<bool, kNumLegs>& touch,
                               const std::array<bool, kNumLegs>& planned) {
  CheckStamp(&contact0_, t_ns, "contact0");
  std::string row = RowStamp(t_ns);
  for (bool c : touch) row += c ? ",1" : ",0";
  for (bool c : planned) row += c ? ",1" : ",0";
  contact0_.file->Write(row + "\n");
}

void EurocRecorder::AddGroundTruth(const GroundTruthState& g) {
  CheckStamp(&gt0_, g.t_ns, "state_groundtruth_estimate0");
  const Eigen::Vector3d& p = g.T_w_body.p_w_x;
  Eigen::Quaterniond q = g.T_w_body.q_w_x.normalized();
  if (q.w() < 0) q.coeffs() = -q.coeffs();  // one sign for the whole file
  std::string row = RowStamp(g.t_ns);
  for (int i = 0; i < 3; ++i) row += "," + Fmt("%.9f", p[i]);
  row += "," + Fmt("%.9f", q.w()) + "," + Fmt("%.9f", q.x()) + "," + Fmt("%.9f", q.y()) + "," +
         Fmt("%.9f", q.z());
  for (int i = 0; i < 3; ++i) row += "," + Fmt("%.9f", g.vel_w_body[i]);
  row += ",0,0,0,0,0,0";  // biases: not part of the ground truth state
  gt0_.file->Write(row + "\n");
}

void EurocRecorder::WriteSensorFiles() const {
  const std::string m = mav0_ + "/";
  WriteFileAtomic(m + "body.yaml",
                  "# The body frame is the IMU frame at the trunk centre: x forward, y left, z up.\n"
                  "comment: viqu robot rat trunk\n");
  WriteFileAtomic(m + "cam0/sensor.yaml",
                  CameraYaml("viqu left camera (rectified, RGB PNG)", rig_.T_body_cam0, rig_, ""));
  WriteFileAtomic(m + "cam1/sensor.yaml",
                  CameraYaml("viqu right camera (rectified, RGB PNG)", rig_.T_body_cam1, rig_, ""));
  if (rig_.camera.depth) {
    WriteFileAtomic(m + "depth0/sensor.yaml",
                    CameraYaml("viqu left camera metric depth along the optical axis",
                               rig_.T_body_cam0, rig_,
                               "\n# Depth images: 16-bit PNG, value * depth_unit_m = depth (m); 0 = no depth.\n"
                               "encoding: 16UC1\ndepth_unit_m: " + Fmt("%.9g", kDepthUnitM) +
                                   "\ninvalid_value: 0\n"));
  }
  if (rig_.camera.segmentation) {
    WriteFileAtomic(m + "seg0/sensor.yaml",
                    CameraYaml("viqu left camera instance segmentation", rig_.T_body_cam0, rig_,
                               "\n# Segmentation images: 16-bit PNG of instance ids; 0 = static background.\n"
                               "encoding: 16UC1\ninstances: instances.csv  # id, category, name\n"
                               "frame_instances: frame_instances.csv  # timestamp [ns], id, category, name\n"));
    std::string csv = "#id,category,name\n";
    for (const auto& [id, seen] : instances_) {
      // The category reported most often; of equally frequent ones, the one seen first.
      Category best = seen.frames.begin()->first;
      for (const auto& [category, n] : seen.frames) {
        const int best_n = seen.frames.at(best);
        if (n > best_n || (n == best_n && seen.first_ns.at(category) < seen.first_ns.at(best))) best = category;
      }
      csv += std::to_string(id) + "," + CategoryName(best) + "," + seen.name + "\n";
    }
    WriteFileAtomic(m + "seg0/instances.csv", csv);
  }
  const double imu_sqrt_rate = std::sqrt(rig_.imu.rate_hz);
  WriteFileAtomic(
      m + "imu0/sensor.yaml",
      "# General sensor definitions.\nsensor_type: imu\ncomment: viqu simulated IMU at the trunk centre\n\n"
      "# Sensor extrinsics wrt. the body-frame.\n" + TransformYaml(Eigen::Isometry3d::Identity()) +
          "rate_hz: " + Fmt("%.9g", rig_.imu.rate_hz) + "\n\n"
          "# inertial sensor noise model parameters (static)\n"
          "gyroscope_noise_density: " + Fmt("%.9g", rig_.imu.gyro_noise / imu_sqrt_rate) +
          "     # [ rad / s / sqrt(Hz) ]\n"
          "gyroscope_random_walk: " + Fmt("%.9g", rig_.imu.gyro_bias_walk) + "       # [ rad / s^2 / sqrt(Hz) ]\n"
          "accelerometer_noise_density: " + Fmt("%.9g", rig_.imu.accel_noise / imu_sqrt_rate) +
          "  # [ m / s^2 / sqrt(Hz) ]\n"
          "accelerometer_random_walk: " + Fmt("%.9g", rig_.imu.accel_bias_walk) + "   # [ m / s^3 / sqrt(Hz) ]\n");
  std::string joint_list;
  for (const char* j : kJointNames) joint_list += std::string(joint_list.empty() ? "" : ", ") + j;
  WriteFileAtomic(m + "joints0/sensor.yaml",
                  "sensor_type: joint_encoders\ncomment: viqu leg joint encoders and foot contact truth\n"
                  "rate_hz: " + Fmt("%.9g", rig_.joints.rate_hz) + "\n"
                  "joints: [" + joint_list + "]  # columns: positions (rad), then velocities (rad/s)\n"
                  "feet: [FL, FR, BL, BR]  # contact columns (1 = touching), then the joints' torques (N m)\n"
                  "noise_rad: " + Fmt("%.9g", rig_.joints.noise_rad) + "\n"
                  "resolution_rad: " + Fmt("%.9g", rig_.joints.resolution_rad) + "\n"
                  "torque_noise_nm: " + Fmt("%.9g", rig_.joints.torque_noise_nm) + "\n"
                  "torque_resolution_nm: " + Fmt("%.9g", rig_.joints.torque_resolution_nm) + "\n"
                  "torque_bias_nm: " + Fmt("%.9g", rig_.joints.torque_bias_nm) + "\n"
                  "torque_delay_s: " + Fmt("%.9g", rig_.joints.torque_delay_s) + "\n"
                  "torque_sampling: " + rig_.joints.torque_sampling + "\n");
  WriteFileAtomic(m + "state_groundtruth_estimate0/sensor.yaml",
                  "sensor_type: visual-inertial\ncomment: ground truth of the body (IMU) frame in the world "
                  "frame (z up), from the simulator; biases are written as 0\n");
}

void EurocRecorder::Finish() {
  if (finished_) return;
  writer_->Drain();
  WriteSensorFiles();
  for (CsvStream* s : {&cam0_, &cam1_, &depth0_, &seg0_, &seg0_frames_, &objects0_, &imu0_, &joints0_, &contact0_, &gt0_}) {
    if (s->file) s->file->Commit();
  }
  // Swap the finished folder into place; an old dataset under the final name is replaced.
  CommitTempDirectory(partial_dir_, final_dir_);
  finished_ = true;
}

}  // namespace viqu::sim
