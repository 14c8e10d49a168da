#include "slam/fusion/visual_leg_fusion.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace viqu::slam {

void VisualLegFusion::BeforeTrack(SlamSystem* system) {
  const Eigen::Isometry3d T_w_c = lo_->T_w_body() * T_body_cam_;
  if (last_T_w_c_) {
    // The translation's uncertainty over the interval: the filter's velocity uncertainty (its
    // largest axis) times the time since the last frame.
    const Eigen::Matrix3d P_vv = lo_->filter().covariance().block<3, 3>(3, 3);
    const double var_v = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(P_vv).eigenvalues().maxCoeff();
    const double sigma_v = std::sqrt(std::max(0.0, var_v));
    system->SetMotionPrior(T_w_c.inverse() * *last_T_w_c_, sigma_v * (lo_->t_ns() - last_t_ns_) * 1e-9);
  }
  last_T_w_c_ = T_w_c;
  last_t_ns_ = lo_->t_ns();
}

void VisualLegFusion::AfterTrack(const TrackResult& r) {
  const bool good = (r.status == TrackStatus::kTracking || r.status == TrackStatus::kRelocalised) &&
                    r.inliers >= min_inliers_;
  if (!good) {
    ++carried_;
    lo_->HoldGravity(false);
    lo_->KeepLevel();
    return;
  }
  const Eigen::Isometry3d T_w_body = r.T_w_c * T_body_cam_.inverse();
  lo_->CorrectPose(T_w_body);
  lo_->HoldGravity(true);
  last_T_w_c_ = r.T_w_c;
  ++corrections_;
}

}  // namespace viqu::slam
