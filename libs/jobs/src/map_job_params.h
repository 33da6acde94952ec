#pragma once
/// \file map_job_params.h
/// Every component's parameters the map job reads, and config_used.ini's text of them.

#include <mrpt/config/CConfigFileBase.h>

#include <string>

#include "roadslam/datasets/kitti_scans.h"
#include "roadslam/gnss_fusion/gnss_fusion.h"
#include "roadslam/pipeline/stage_factory.h"
#include "roadslam/pipeline/vehicle_prior.h"
#include "roadslam/velodyne/decoder_params.h"

namespace roadslam::jobs {

struct MapJobParams {
  pipeline::ChainParams chain;
  velodyne::DecoderParams decoder;
  datasets::KittiParams kitti;
  pipeline::VehiclePriorParams vehicle_prior;  ///< read by CanPriorStream with --can; recorded always
  gnss_fusion::GnssFusionParams gnss_fusion;   ///< [gnss_fusion], read by --gnss; recorded always

  void load(const mrpt::config::CConfigFileBase& cfg);
  std::string used() const;  ///< config_used.ini
};

}  // namespace roadslam::jobs
