#pragma once
/// \file recording_open.h
/// What roadslam-view opens for the recording a user names: a rawlog or a roadslam-grab session
/// folder as it is; a Velodyne pcap or a KITTI folder of .bin sweeps converted into a rawlog in the
/// RecordingCache (once: a later run reuses the conversion while the input is unchanged). A damaged
/// input is converted up to its damage, and the damage is stated in sources::damageWarning()'s words,
/// on every open (the cache keeps it beside the conversion as "<conversion>.damage").

#include <ostream>
#include <string>

#include "roadslam/viewer/recording_cache.h"

namespace roadslam::viewer {

struct RecordingToOpen {
  std::string rawlog;  ///< the rawlog, or the roadslam-grab session folder, to open
  std::string damage;  ///< the input's damage (sources::damageWarning), empty when it read whole
};

/// The recording to open for \p path, converting it into \p cache when it is a pcap or a KITTI folder
/// (telling \p err). Throws std::runtime_error naming \p path when it holds no sweep before its end
/// or its damage; nothing of a failed conversion is left in the cache.
RecordingToOpen recordingToOpen(const std::string& path, RecordingCache& cache, std::ostream& err);

}  // namespace roadslam::viewer
