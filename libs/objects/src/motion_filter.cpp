#include "roadslam/objects/motion_filter.h"

#include "ctrv_filter.h"
#include "cv_filter.h"
#include "imm_filter.h"

namespace roadslam::objects {

std::unique_ptr<MotionFilter> makeMotionFilter(const TrackerParams& p) {
  switch (p.motion_model) {
    case MotionModel::ConstantVelocity: return std::make_unique<CvFilter>(p.accel_sigma_mps2);
    case MotionModel::Ctrv: return std::make_unique<CtrvFilter>(p.ctrv);
    case MotionModel::Imm: return std::make_unique<ImmFilter>(p.imm);
  }
  return std::make_unique<CvFilter>(p.accel_sigma_mps2);
}

}  // namespace roadslam::objects
