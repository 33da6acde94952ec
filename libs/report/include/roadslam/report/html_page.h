#pragma once
/// \file html_page.h
/// One self-contained HTML page: headings, text, tables, inline SVG and PNGs embedded as data URIs
/// (RFC 2397, base64 per RFC 4648), one small style sheet inline. The page fetches nothing, so it
/// opens the same offline, from a cluster's shared disk, or attached to a mail.

#include <string>
#include <vector>

namespace roadslam::report {

/// &, <, >, " and ' as entities (text and attribute values).
std::string htmlEscape(const std::string& text);
/// RFC 4648 base64 with padding.
std::string base64(const std::string& bytes);

class HtmlPage {
 public:
  explicit HtmlPage(std::string title);

  void heading(const std::string& text, int level = 2);
  void paragraph(const std::string& text);
  /// A paragraph of pre-formatted text (logs, commands).
  void code(const std::string& text);
  /// \p rows of cells, each as many as \p header; numbers are best formatted by the caller.
  /// Cells of the \p highlight_rows (row indices) are shown in bold.
  void table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
             const std::vector<size_t>& highlight_rows = {});
  /// Markup made by this library (svgPlot); inserted as it is.
  void svg(const std::string& svg_markup);
  /// A PNG file embedded as a data URI; throws std::runtime_error naming it when it cannot be read.
  void pngFile(const std::string& path, const std::string& alt, int width_px = 0);

  std::string str() const;
  /// Writes the page atomically (common/atomic_file.h).
  void write(const std::string& path) const;

 private:
  std::string title_;
  std::string body_;
};

}  // namespace roadslam::report
