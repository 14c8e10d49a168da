#pragma once
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <string>

#include <Eigen/Geometry>

#include "common/atomic_output_file.h"
#include "sim/image_write_queue.h"
#include "scenario/scenario.h"
#include "slam/measurements/ground_truth_pose.h"
#include "slam/measurements/imu_sample.h"
#include "slam/measurements/joint_state.h"
#include "slam/measurements/object_truth.h"
#include "slam/measurements/stereo_frame.h"

namespace viqu::sim {

// The rig that a recording describes in its sensor.yaml files.
struct EurocRig {
  CameraConfig camera;            // rate and resolution; depth/segmentation enable depth0/seg0
  PinholeIntrinsics intrinsics;   // rectified pinhole intrinsics, the same for both cameras
  Eigen::Isometry3d T_body_cam0 = Eigen::Isometry3d::Identity();  // left camera (optical) in body
  Eigen::Isometry3d T_body_cam1 = Eigen::Isometry3d::Identity();  // right camera (optical) in body
  ImuConfig imu;                  // rate and noise figures; the IMU frame is the body frame
  JointsConfig joints;            // encoder rate and noise
  std::string urdf_path;          // the robot's URDF, copied to mav0/robot.urdf ("" = none)
};

// Records a run in the EuRoC MAV layout, which stereo(-inertial) SLAM systems read as is:
//
//   DATASET/mav0/body.yaml
//   DATASET/mav0/cam0/{data/<t_ns>.png, data.csv, sensor.yaml}     left RGB
//   DATASET/mav0/cam1/{data/<t_ns>.png, data.csv, sensor.yaml}     right RGB
//   DATASET/mav0/depth0/{data/<t_ns>.png, data.csv, sensor.yaml}   left depth, 16-bit PNG, 1/5000 m
//                                                                  (sensor.yaml depth_unit_m 0.0002)
//   DATASET/mav0/seg0/{data/<t_ns>.png, data.csv, sensor.yaml, instances.csv,
//                      frame_instances.csv}                        left instance ids
//   DATASET/mav0/objects0/data.csv                                 the movable objects' truth per frame
//                                                                  (with seg0): scores a replay's
//                                                                  dynamic-object decisions
//   DATASET/mav0/imu0/{data.csv, sensor.yaml}
//   DATASET/mav0/joints0/{data.csv, sensor.yaml}                   encoders, foot contacts (truth) and
//                                                                  the servos' torques
//   DATASET/mav0/contact0/data.csv                                 foot touch sensors and the
//                                                                  gait's planned stance
//   DATASET/mav0/robot.urdf                                        the robot's kinematics
//   DATASET/mav0/state_groundtruth_estimate0/{data.csv, sensor.yaml}  trunk (IMU) pose in world
//
// seg0 describes the ids twice. instances.csv ("id,category,name", the format of a masks folder,
// docs/MASKS.md) has one row per id seen in the run: its name as first seen and the category it
// was reported with most often (ties: the one seen first); a detector model with wrong
// categories (sensors.segmentation.wrong_category_rate) reports one id under several.
// frame_instances.csv ("timestamp [ns],id,category,name") has, for every segmentation image,
// one row per entry of the frame's StereoFrame::instances as given (background and robot
// included, in the frame's order), so that a replay gives the dynamic-object stage exactly the
// instance list that the live run gave it; a frame whose list was empty has no row.
//
// objects0/data.csv ("timestamp [ns],visible_px,truly_moving,category,name") has, per frame, one
// row per movable object visible in the ideal instance image (before the detector model): its
// pixels there and whether it truly moved (runner/dynamic_score.h); a frame with none has no row.
//
// Everything is written under DATASET.partial/ (CSV files through temporary names) and renamed
// onto DATASET by Finish(); destroyed without Finish(), the recorder removes DATASET.partial.
// Timestamps of each stream must increase. Errors throw RunError. Threads: AddFrame shares no
// state with AddImu, AddJoints, AddContact and AddGroundTruth, so it may be called on another
// thread than they are, nor with AddObjectTruth (each of the two groups from one thread at a time); Finish after both. IMU and encoder values are
// written with as many digits as they need to read back exactly (at most 17), so that a replay
// gets the very doubles of the run.
class EurocRecorder {
 public:
  // `dataset_dir` is the final folder (e.g. RUN/dataset); a stale DATASET.partial is replaced.
  EurocRecorder(const std::string& dataset_dir, const EurocRig& rig);
  ~EurocRecorder();
  EurocRecorder(const EurocRecorder&) = delete;
  EurocRecorder& operator=(const EurocRecorder&) = delete;

  // Left/right RGB (CV_8UC3, RGB order), and depth/segmentation when present and enabled.
  // `depth_steps`, when given, is the depth already in steps of 1/5000 m (sim::QuantiseDepth's
  // result): it is written as is (and must not be modified afterwards) instead of converted.
  void AddFrame(const StereoFrame& frame, const cv::Mat& depth_steps = cv::Mat());
  void AddImu(const ImuSample& sample);
  void AddJoints(const JointState& joints);
  // The touch sensors' reading and the controller's planned stance at an encoder sample.
  void AddContact(int64_t t_ns, const std::array<bool, kNumLegs>& touch, const std::array<bool, kNumLegs>& planned);
  void AddGroundTruth(const GroundTruthState& state);
  // The movable objects' truth at a camera frame (written only with segmentation enabled).
  void AddObjectTruth(int64_t t_ns, const std::vector<ObjectTruth>& objects);
  // Writes the sensor.yaml files, commits the CSV files and renames the folder into place.
  void Finish();

  const std::string& dataset_dir() const { return final_dir_; }
  const std::string& partial_dir() const { return partial_dir_; }

 private:
  // One CSV file with the stamp of its last row.
  struct CsvStream {
    std::unique_ptr<AtomicOutputFile> file;  // data.csv under its temporary name
    int64_t last_t_ns = std::numeric_limits<int64_t>::min();  // stamp of the last row (ns)
  };
  CsvStream OpenCsv(const std::string& folder, const std::string& header) const;
  void CheckStamp(CsvStream* s, int64_t t_ns, const char* what) const;
  // `image` goes to the write queue as it is: a copy, or a Mat nobody modifies afterwards.
  void WriteImage(const std::string& folder, CsvStream* csv, int64_t t_ns, cv::Mat image, PngContent content);
  void WriteSensorFiles() const;

  std::string final_dir_;    // DATASET
  std::string partial_dir_;  // DATASET.partial
  std::string mav0_;         // DATASET.partial/mav0
  EurocRig rig_;
  CsvStream cam0_, cam1_, depth0_, seg0_, imu0_, joints0_, contact0_, gt0_;
  CsvStream objects0_;       // objects0/data.csv
  CsvStream seg0_frames_;    // seg0/frame_instances.csv
  // An id seen in the segmentation, for seg0/instances.csv.
  struct SeenInstance {
    std::string name;                       // as first seen
    std::map<Category, int> frames;         // frames reported under each category
    std::map<Category, int64_t> first_ns;   // stamp of the first frame under each category (ns)
  };
  std::map<uint16_t, SeenInstance> instances_;
  std::unique_ptr<ImageWriteQueue> writer_ = std::make_unique<ImageWriteQueue>();  // PNG encoding
  bool finished_ = false;    // Finish() succeeded
};

}  // namespace viqu::sim
