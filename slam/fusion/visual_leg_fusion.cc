#include "slam/fusion/visual_leg_fusion.h"

namespace viqu::slam {

void VisualLegFusion::BeforeTrack(SlamSystem* system) {
  const Eigen::Isometry3d T_w_c = lo_->T_w_body() * T_body_cam_;
  if (last_T_w_c_) system->SetMotionPrior(T_w_c.inverse() * *last_T_w_c_);
  last_T_w_c_ = T_w_c;
}

void VisualLegFusion::AfterTrack(const TrackResult& r) {
  const bool good = (r.status == TrackStatus::kTracking || r.status == TrackStatus::kRelocalised) &&
                    r.inliers >= min_inliers_;
  if (!good) {
    ++carried_;
    return;
  }
  const Eigen::Isometry3d T_w_body = r.T_w_c * T_body_cam_.inverse();
  lo_->CorrectPose(T_w_body);
  last_T_w_c_ = r.T_w_c;
  ++corrections_;
}

}  // namespace viqu::slam
