// libFuzzer target: the text parts of the dataset readers (slam/io): the first byte picks the
// reader, the rest is the file. EuRoC image lists and ground truth, EuRoC/viqu sensor.yaml
// (OpenCV-flavoured YAML), TUM image lists and camera files (viqu and ORB-SLAM2/3), and a viqu
// recording's imu0 stream through the proprioception reader (io::ReadImuCsv, which also reads
// EuRoC's imu0 for the gyro's motion prior); `--masks` folders (instances.csv, and a mask image
// of a 64x48 frame through InstanceMaskFolder::Read: the PNG check, the decoder, the size and id
// checks), a recording's seg0/frame_instances.csv and objects0/data.csv. Camera files are checked
// against their image size inside ReadCameraFile (slam/io/calibration_check.h).
#include <filesystem>

#include "common/errors.h"
#include "fuzz/fuzz_input_file.h"
#include "slam/io/camera_file.h"
#include "slam/io/euroc_ground_truth.h"
#include "slam/io/euroc_sensor_yaml.h"
#include "slam/io/image_list.h"
#include "slam/io/instance_mask_folder.h"
#include "slam/io/object_truth_csv.h"
#include "slam/io/proprioception_reader.h"
#include "slam/io/segment_instances.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const uint8_t which = data[0] % 11;
  ++data;
  --size;
  const std::string dir = viqu::fuzz::WorkDir().string();
  try {
    switch (which) {
      case 0: viqu::io::ReadEurocImageList(viqu::fuzz::WriteInput("list.csv", data, size), dir); break;
      case 1: viqu::io::ReadEurocGroundTruth(viqu::fuzz::WriteInput("gt.csv", data, size)); break;
      case 2: viqu::io::ReadEurocCameraSensor(viqu::fuzz::WriteInput("sensor.yaml", data, size)); break;
      case 3: viqu::io::ReadEurocSensorTransform(viqu::fuzz::WriteInput("imu.yaml", data, size)); break;
      case 4: viqu::io::ReadTumImageList(viqu::fuzz::WriteInput("rgb.txt", data, size), dir); break;
      case 5: viqu::io::ReadCameraFile(viqu::fuzz::WriteInput("camera.yaml", data, size)); break;
      case 7:
        viqu::fuzz::WriteInput("masks_csv/instances.csv", data, size);
        viqu::io::InstanceMaskFolder((viqu::fuzz::WorkDir() / "masks_csv").string());
        break;
      case 8: {
        static const bool made = [] {
          const char csv[] = "id,category,name\n1,person,alice\n2,box,crate\n";
          viqu::fuzz::WriteInput("masks/instances.csv", reinterpret_cast<const uint8_t*>(csv), sizeof csv - 1);
          return true;
        }();
        (void)made;
        viqu::fuzz::WriteInput("masks/frame.png", data, size);
        const viqu::io::InstanceMaskFolder masks((viqu::fuzz::WorkDir() / "masks").string());
        masks.Read("images/frame.png", cv::Size(64, 48));
        break;
      }
      case 9: viqu::io::ReadFrameInstances(viqu::fuzz::WriteInput("frame_instances.csv", data, size)); break;
      case 10:
        viqu::fuzz::WriteInput("objects/mav0/objects0/data.csv", data, size);
        viqu::io::ReadViquObjectTruth((viqu::fuzz::WorkDir() / "objects").string());
        break;
      default: {
        // The other streams present and empty: the imu0 rows are what is fuzzed.
        static const bool made = [] {
          const uint8_t none[] = {'#', '\n'};
          for (const char* f : {"rec/mav0/joints0/data.csv", "rec/mav0/contact0/data.csv", "rec/mav0/robot.urdf"}) {
            viqu::fuzz::WriteInput(f, none, sizeof none);
          }
          return true;
        }();
        (void)made;
        viqu::fuzz::WriteInput("rec/mav0/imu0/data.csv", data, size);
        viqu::io::ReadViquProprioception((viqu::fuzz::WorkDir() / "rec").string());
        break;
      }
    }
  } catch (const viqu::InputError&) {
  }
  return 0;
}
