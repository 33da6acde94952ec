#pragma once
/// \file map_folder.h
/// A map folder as the unit a user keeps: besides the maps (map_outputs.h), `map.json` says
/// what the folder is and which version wrote it, and `keyframes.bin` holds every keyframe at its optimised
/// pose with its points and its Scan Context descriptor, so a later run can recognise places in it and
/// register against it.
///
/// map.json: {"format": "roadslam-map", "version": 1, "keyframes": N, "keyframes_file": "keyframes.bin",
///            "scan_context": {"num_rings", "num_sectors", "max_radius_m", "height_offset_m"}}
/// keyframes.bin (little-endian): "RSKF", u32 version, u64 N, then per keyframe: u64 frame_index,
///   f64 stamp_s, f64 path_m, f64[12] T_map_kf (3x4, row-major), u32 n_points, f32[3 n] points (lidar frame,
///   m), u32 rings, u32 sectors, f32[rings x sectors] Scan Context bins (row-major).
/// Reading fails with a std::runtime_error naming the file: a folder without map.json (older roadslam, or
/// not a roadslam map), another format, another version, a truncated or damaged keyframes.bin.

#include <string>
#include <vector>

#include "roadslam/mapping/loop_closure.h"
#include "roadslam/mapping/pose_graph.h"
#include "roadslam/place/scan_context.h"

namespace roadslam::mapping {

/// The version this build writes and reads [-].
constexpr int kMapFolderVersion = 1;

/// A map folder's keyframes as read back.
struct MapFolder {
  int version = 0;
  std::vector<Keyframe> keyframes;   ///< points_lidar and descriptor filled; T_odom_lidar = T_map_kf
  PoseVector T_map_kf;               ///< optimised keyframe poses [m]
  place::ScanContextParams scan_context;  ///< the descriptors' parameters
};

/// Writes map.json and keyframes.bin into \p dir. Keyframes without a descriptor get one computed with
/// \p sc. Throws naming the file on a write error.
void writeMapFolder(const std::string& dir, const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf,
                    const place::ScanContextParams& sc);

/// Reads a folder written by writeMapFolder; throws std::runtime_error naming the file and the problem.
MapFolder readMapFolder(const std::string& dir);

}  // namespace roadslam::mapping
