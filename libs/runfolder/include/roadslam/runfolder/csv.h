#pragma once
/// \file csv.h
/// The run folder's CSV files: comma-separated, one header line naming the columns, no quoting (text
/// cells have their commas replaced by ';' when written). Read by column name, so the columns may come
/// in any order and extra columns are ignored; a column the reader needs that the header lacks fails
/// naming the file and the column, and so does a cell that is not a number, with its line.

#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace roadslam::runfolder {

/// One CSV file read row by row.
class CsvReader {
 public:
  /// Opens \p path and reads its header; throws naming the file when it cannot be read, has no header
  /// or lacks one of \p needed.
  CsvReader(const std::string& path, const std::vector<std::string>& needed);
  bool next();  ///< the next row; false at the end (empty lines are skipped)
  const std::string& text(const std::string& column) const;  ///< the cell ("" when the row is short)
  double number(const std::string& column) const;            ///< finite; throws naming file:line and column
  double real(const std::string& column) const;              ///< as number(), nan and inf allowed ("nan", "-nan", "inf")
  long integer(const std::string& column) const;             ///< a number that must be whole
  bool flag(const std::string& column) const { return integer(column) != 0; }
  const std::string& path() const { return path_; }
  size_t line() const { return line_; }

 private:
  size_t column(const std::string& name) const;
  std::string path_;
  std::ifstream in_;
  std::map<std::string, size_t> col_;
  std::vector<std::string> row_;
  size_t line_ = 1;  ///< lines read, the header included
};

/// Splits a line at every comma (an empty last cell included).
std::vector<std::string> splitCsvLine(const std::string& line);

/// \p s with its commas replaced by ';' (a text cell).
std::string csvText(std::string s);

/// printf into a std::string (the writers' fixed formats).
std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

}  // namespace roadslam::runfolder
