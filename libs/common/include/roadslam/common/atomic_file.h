#pragma once
/// \file atomic_file.h
/// Outputs are written to "<path>.tmp-<pid>" and renamed over <path> on commit, so a crash or a
/// SIGKILL never leaves a half-written file behind (rename(2) is atomic within one filesystem), and a
/// failed write leaves no temporary file: the writers remove it when they go out of scope uncommitted.
/// Errors name the file and the system's reason (strerror: "No space left on device").

#include <memory>
#include <ostream>
#include <string>

namespace roadslam {

/// A file written through a stream of our own (a write(2)-backed buffer that keeps the errno of the
/// first failed write, which std::ofstream loses).
class AtomicFile {
 public:
  /// Opens the temporary file; throws std::runtime_error naming \p path and the reason when it cannot
  /// be created. \p mode is accepted for std::ofstream compatibility: the file is always truncated.
  explicit AtomicFile(std::string path, std::ios::openmode mode = std::ios::out | std::ios::trunc);
  ~AtomicFile();  ///< Removes the temporary file when commit() was not called.
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream();
  const std::string& tempPath() const { return tmp_; }
  /// Flushes, fsyncs and renames onto the final path; throws "cannot write 'PATH': REASON" on any
  /// I/O error (the temporary file is removed).
  void commit();

 private:
  struct Impl;
  std::string path_, tmp_;
  std::unique_ptr<Impl> impl_;
  bool committed_ = false;
};

/// Writes \p contents to \p path atomically (see AtomicFile).
void writeFileAtomically(const std::string& path, const std::string& contents);

/// A temporary name for a file that a library writes itself (MRPT, octomap, an image encoder):
/// write to path(), then commit(); the temporary file is removed when the object goes out of scope
/// uncommitted (an exception on the way).
class TempFile {
 public:
  /// \p extension is appended to the temporary name where the library picks its format by it (".png").
  explicit TempFile(std::string final_path, const std::string& extension = "");
  ~TempFile();
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  const std::string& path() const { return tmp_; }
  /// fsync + rename onto the final path; throws naming the final path and the reason.
  void commit();
  /// "cannot write 'FINAL': REASON" for a library's failed write, the reason from errno when the
  /// library left one, else from the file system (no space left), else "write error".
  std::string failure(const std::string& what = "") const;

 private:
  std::string path_, tmp_;
  bool committed_ = false;
};

/// Temporary name used for \p path.
std::string tempPathFor(const std::string& path);
/// fsync + rename \p tmp_path onto \p final_path; on failure removes \p tmp_path and throws
/// "cannot write 'FINAL': REASON".
void commitTempFile(const std::string& tmp_path, const std::string& final_path);

/// The reason a write into \p path failed: strerror(\p err) when it is set, else "No space left on
/// device" when \p path's file system has no free block, else "write error".
std::string writeErrorReason(const std::string& path, int err);

}  // namespace roadslam
