#pragma once
/// \file candump.h
/// The can-utils log format, read and written exactly as `candump -l` writes and `canplayer` reads it:
///
///     (1436509052.249713) can0 123#DEADBEEF         classic frame, 11-bit id (3 hex digits)
///     (1436509052.249713) can0 12345678#00112233    29-bit id (8 hex digits)
///     (1436509052.249713) can0 123#R                remote frame, len 0;  123#R5: remote, len 5
///     (1436509052.249713) can0 123##1DEADBEEF       CAN FD, flags nibble (1 = BRS, 2 = ESI), data
///     (1436509052.249713) can0 20000080#0000000000000000   error frame (CAN_ERR_FLAG in the id)
///     (1436509052.249713) can0 123#1122334455667788_E      classic frame with len8_dlc 9..F
/// Data bytes may be separated by '.', hex digits are written upper case. See can-utils lib.h.
/// Bad lines never stop a read: they are counted and reported with their line numbers.

#include <roadslam/can/frame.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace roadslam::can {

/// Parses one log line (without the newline). On failure returns false and sets \p error to a
/// static description; never allocates, never throws.
bool parseCandumpLine(std::string_view line, CanFrame& out, const char** error) noexcept;

/// Parses the frame part only ("123#DEADBEEF"), as `cansend` takes it.
bool parseFrameText(std::string_view text, CanFrame& out, const char** error) noexcept;

/// Writes one line (with '\n') into \p buf; returns its length (0 if \p cap is too small).
/// The largest line needs fewer than 220 bytes.
std::size_t formatCandumpLine(const CanFrame& frame, char* buf, std::size_t cap) noexcept;
std::string formatCandumpLine(const CanFrame& frame);

/// One rejected line of a log.
struct CandumpIssue {
  std::size_t line = 0;  ///< 1-based line number
  std::string reason;    ///< why it was rejected
  std::string text;      ///< the line, cut to 80 characters
};

/// Counts of a read; the first `max_issues` problems are kept with their line numbers.
struct CandumpStats {
  std::size_t lines = 0;       ///< lines read
  std::size_t frames = 0;      ///< frames returned
  std::size_t empty = 0;       ///< blank or comment ('#') lines
  std::size_t bad = 0;         ///< lines rejected
  bool truncated_tail = false; ///< last line had no newline and did not parse (cut-off log)
  std::vector<CandumpIssue> issues;
};

/// Streaming reader of a candump log; bad lines are skipped, counted and remembered.
class CandumpReader {
 public:
  /// Opens \p path; throws std::runtime_error naming the file if it cannot be opened.
  explicit CandumpReader(const std::string& path, std::size_t max_issues = 100);
  /// Reads from a stream the caller keeps alive; \p name is used in reports.
  CandumpReader(std::istream& in, std::string name, std::size_t max_issues = 100);
  ~CandumpReader();
  CandumpReader(const CandumpReader&) = delete;
  CandumpReader& operator=(const CandumpReader&) = delete;

  /// Next good frame; false at end of input.
  bool next(CanFrame& frame);
  const CandumpStats& stats() const { return stats_; }
  const std::string& name() const { return name_; }

 private:
  std::unique_ptr<std::ifstream> file_;
  std::istream* in_;
  std::string name_;
  std::size_t max_issues_;
  std::string line_;
  CandumpStats stats_;
};

/// Reads a whole log; bad lines are reported in \p stats (optional).
std::vector<CanFrame> readCandumpFile(const std::string& path, CandumpStats* stats = nullptr);
/// The times of a log's first and last good frames [s since epoch], read from its head and its tail
/// only (a log of hours opens at once); nullopt when it has no good frame. Throws naming the file
/// when it cannot be opened.
struct CandumpSpan {
  double first_s = 0, last_s = 0;
};
std::optional<CandumpSpan> candumpSpan(const std::string& path);

/// Writes frames as a candump log (atomically: to a temporary file, then renamed).
void writeCandumpFile(const std::string& path, const std::vector<CanFrame>& frames);

}  // namespace roadslam::can
