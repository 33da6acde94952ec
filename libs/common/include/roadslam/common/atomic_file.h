#pragma once
/// \file atomic_file.h
/// Outputs are written to "<path>.tmp-<pid>" and renamed over <path> on commit, so a crash or a
/// SIGKILL never leaves a half-written file behind (rename(2) is atomic within one filesystem).

#include <fstream>
#include <string>

namespace roadslam {

class AtomicFile {
 public:
  /// Opens the temporary file; throws std::runtime_error naming \p path when it cannot be created.
  explicit AtomicFile(std::string path, std::ios::openmode mode = std::ios::out | std::ios::trunc);
  ~AtomicFile();  ///< Removes the temporary file when commit() was not called.
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return out_; }
  const std::string& tempPath() const { return tmp_; }
  /// Flushes, fsyncs and renames onto the final path; throws naming the path on any I/O error.
  void commit();

 private:
  std::string path_, tmp_;
  std::ofstream out_;
  bool committed_ = false;
};

/// Writes \p contents to \p path atomically (see AtomicFile).
void writeFileAtomically(const std::string& path, const std::string& contents);

/// Temporary name used for \p path: callers that write through a library (MRPT, octomap) write there,
/// then call commitTempFile().
std::string tempPathFor(const std::string& path);
void commitTempFile(const std::string& tmp_path, const std::string& final_path);

}  // namespace roadslam
