#pragma once
/// \file recording_cache.h
/// Where roadslam-view keeps what it makes from a recording (a pcap or a KITTI folder converted into
/// a rawlog, the rawlog index of any rawlog it opens): never beside its input, but in the user's
/// cache folder, $XDG_CACHE_HOME/roadslam (else $HOME/.cache/roadslam), each file named
/// "<stem>-<key><ext>". The key is 16 hex digits of a hash of the input's identity: its canonical
/// absolute path, size, modification time [ns] and first 64 KiB; for a folder, the name, size and
/// modification time of each of its files, those of the times.txt one level up (a KITTI odometry
/// sequence's), and the first 64 KiB of its first file. Two inputs of the same name have two keys,
/// and a changed input a new one: it is converted again.
///
/// When the cache folder cannot be created or written (or the user asks for none: --no-index-cache),
/// conversions go into a private temporary folder (mkdtemp, mode 0700) removed when the
/// RecordingCache is destroyed, and no index is kept.

#include <string>

#include "roadslam/rawlog/rawlog_index.h"

namespace roadslam::viewer {

/// The user's cache folder for roadslam: $XDG_CACHE_HOME/roadslam when XDG_CACHE_HOME is an absolute
/// path (the XDG base directory spec ignores a relative one), else $HOME/.cache/roadslam; empty
/// when neither is set.
std::string userCacheFolder();

/// 16 lower-case hex digits of the FNV-1a 64-bit hash of \p path's identity (see the file comment).
/// Throws std::runtime_error naming \p path when it cannot be read.
std::string identityKey(const std::string& path);

/// "<stem>-<identityKey(path)><ext>": the stem of a file's name (velodyne.pcap: velodyne), or a
/// folder's name.
std::string cacheFileName(const std::string& path, const std::string& ext);

class RecordingCache {
 public:
  /// \p persistent: the user's cache folder, when it can be created and written; false: a private
  /// temporary folder (--no-index-cache).
  explicit RecordingCache(bool persistent);
  /// Removes the private temporary folder, if one was made.
  ~RecordingCache();
  RecordingCache(const RecordingCache&) = delete;
  RecordingCache& operator=(const RecordingCache&) = delete;

  /// True when the user's cache folder is in use.
  bool persistent() const { return persistent_; }
  /// Why the user's cache folder is not in use although it was asked for (empty otherwise).
  const std::string& note() const { return note_; }
  /// The file in the cache for \p input with extension \p ext (".rawlog"): in the user's cache
  /// folder, else in the private temporary folder (made on first use; throws when it cannot be).
  std::string fileFor(const std::string& input, const std::string& ext);
  /// Points \p opt's index file into the user's cache folder; without one, keeps none (a fresh
  /// sidecar beside the rawlog is still read unless \p opt.use_cache is off).
  void configureIndex(rawlog::RawlogIndexOptions& opt) const;

 private:
  bool persistent_ = false;
  std::string folder_, note_;
  std::string private_;  // the private temporary folder, once made
};

}  // namespace roadslam::viewer
