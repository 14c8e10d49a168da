#include "slam/fusion/visual_leg_fusion.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace viqu::slam {

void VisualLegFusion::BeforeTrack(SlamSystem* system) {
  if (const std::optional<Prior> p = NextPrior()) system->SetMotionPrior(p->T_cur_last, p->sigma_m);
}

std::optional<VisualLegFusion::Prior> VisualLegFusion::NextPrior() {
  const Eigen::Isometry3d T_w_c = lo_->T_w_body() * T_body_cam_;
  std::optional<Prior> p;
  if (last_T_w_c_) {
    // The translation's uncertainty over the interval: the filter's velocity uncertainty (its
    // largest axis) times the time since the last frame.
    const Eigen::Matrix3d P_vv = lo_->filter().covariance().block<3, 3>(3, 3);
    const double var_v = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(P_vv).eigenvalues().maxCoeff();
    const double sigma_v = std::sqrt(std::max(0.0, var_v));
    p = Prior{T_w_c.inverse() * *last_T_w_c_, sigma_v * (lo_->t_ns() - last_t_ns_) * 1e-9};
  }
  last_T_w_c_ = T_w_c;
  last_t_ns_ = lo_->t_ns();
  return p;
}

void VisualLegFusion::AfterTrack(const TrackResult& r) {
  const bool good = (r.status == TrackStatus::kTracking || r.status == TrackStatus::kRelocalised) &&
                    r.inliers >= min_inliers_;
  // The next prior is the motion from the pose the tracker gave this frame to the filter's pose
  // then, so the tracker's prediction is the filter's pose even when vision tracked this frame
  // too weakly to correct the filter (its pose must not become the base of the carried ones).
  // The rotation is made orthonormal again: the tracker applies the prior to its own pose, whose
  // inverse the output is, and over a run of carried frames a rotation kept as given would
  // square its rounding error at every frame (a 5 s dropout ended in NaN).
  last_T_w_c_ = r.T_w_c;
  last_T_w_c_->linear() = Eigen::Quaterniond(r.T_w_c.linear()).normalized().toRotationMatrix();
  if (!good) {
    ++carried_;
    lo_->Carried();
    lo_->KeepLevel();
    return;
  }
  const Eigen::Isometry3d T_w_body = r.T_w_c * T_body_cam_.inverse();
  lo_->CorrectPose(T_w_body);
  lo_->HoldGravity(true);
  ++corrections_;
}

}  // namespace viqu::slam
