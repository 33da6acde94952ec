#include "map_job_params.h"

#include <mrpt/config/CConfigFileMemory.h>

#include "roadslam/jobs/map_job.h"

namespace roadslam::jobs {

void MapJobParams::load(const mrpt::config::CConfigFileBase& cfg) {
  chain.objects.loadFromConfigFile(cfg, "objects", "preprocess");
  chain.tracking.loadFromConfigFile(cfg, "tracking");
  chain.odometry.loadFromConfigFile(cfg);
  decoder.loadFromConfigFile(cfg, "velodyne");
  kitti.loadFromConfigFile(cfg, "kitti");
  vehicle_prior.loadFromConfigFile(cfg, "vehicle_prior");
  chain.mapper.loadFromConfigFile(cfg);
  chain.maps.loadFromConfigFile(cfg);
  gnss_fusion.loadFromConfigFile(cfg, "gnss_fusion");
  chain.localizer.loadFromConfigFile(cfg);
  chain.localizer.global = chain.mapper.loop.global;
}

std::string MapJobParams::used() const {
  mrpt::config::CConfigFileMemory out;
  chain.odometry.saveToConfigFile(out);
  decoder.saveToConfigFile(out, "velodyne");
  kitti.saveToConfigFile(out, "kitti");
  vehicle_prior.saveToConfigFile(out, "vehicle_prior");
  chain.mapper.saveToConfigFile(out);
  chain.maps.saveToConfigFile(out);
  chain.objects.saveToConfigFile(out, "objects");
  chain.tracking.saveToConfigFile(out, "tracking");
  gnss_fusion.saveToConfigFile(out, "gnss_fusion");
  chain.localizer.saveToConfigFile(out);
  return out.getContent();
}

std::string effectiveMapConfig(const mrpt::config::CConfigFileBase& cfg) {
  MapJobParams params;
  params.load(cfg);
  return params.used();
}

}  // namespace roadslam::jobs
