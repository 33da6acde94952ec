#include "roadslam/report/html_page.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"

namespace roadslam::report {
namespace {

constexpr const char* kStyle =
    "body{font-family:sans-serif;margin:2em;max-width:1200px;color:#222}"
    "table{border-collapse:collapse;margin:0.5em 0 1.5em 0;font-size:0.9em}"
    "th,td{border:1px solid #ccc;padding:0.25em 0.6em;text-align:right}"
    "th{background:#f0f0f0}td:first-child,th:first-child{text-align:left}"
    "tr.best td{font-weight:bold;background:#eef7ee}"
    "pre{background:#f6f6f6;padding:0.6em;overflow-x:auto;font-size:0.85em}"
    "svg{margin:0.5em 0}";

}  // namespace

std::string htmlEscape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string base64(const std::string& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += k[(v >> 18) & 63], out += k[(v >> 12) & 63], out += k[(v >> 6) & 63], out += k[v & 63];
  }
  if (i < bytes.size()) {
    const bool two = i + 1 < bytes.size();
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (two ? static_cast<unsigned char>(bytes[i + 1]) << 8 : 0);
    out += k[(v >> 18) & 63], out += k[(v >> 12) & 63];
    out += two ? k[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

HtmlPage::HtmlPage(std::string title) : title_(std::move(title)) { heading(title_, 1); }

void HtmlPage::heading(const std::string& text, int level) {
  const std::string h = "h" + std::to_string(level < 1 ? 1 : level > 4 ? 4 : level);
  body_ += "<" + h + ">" + htmlEscape(text) + "</" + h + ">\n";
}

void HtmlPage::paragraph(const std::string& text) { body_ += "<p>" + htmlEscape(text) + "</p>\n"; }

void HtmlPage::code(const std::string& text) { body_ += "<pre>" + htmlEscape(text) + "</pre>\n"; }

void HtmlPage::table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
                     const std::vector<size_t>& highlight_rows) {
  body_ += "<table>\n<tr>";
  for (const auto& h : header) body_ += "<th>" + htmlEscape(h) + "</th>";
  body_ += "</tr>\n";
  for (size_t r = 0; r < rows.size(); ++r) {
    bool best = false;
    for (size_t h : highlight_rows) best = best || h == r;
    body_ += best ? "<tr class=\"best\">" : "<tr>";
    for (const auto& c : rows[r]) body_ += "<td>" + htmlEscape(c) + "</td>";
    body_ += "</tr>\n";
  }
  body_ += "</table>\n";
}

void HtmlPage::svg(const std::string& svg_markup) { body_ += svg_markup + "\n"; }

void HtmlPage::pngFile(const std::string& path, const std::string& alt, int width_px) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read picture '" + path + "'");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  body_ += "<p><img alt=\"" + htmlEscape(alt) + "\"" + (width_px > 0 ? " width=\"" + std::to_string(width_px) + "\"" : "") +
           " src=\"data:image/png;base64," + base64(bytes.str()) + "\"></p>\n";
}

std::string HtmlPage::str() const {
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + htmlEscape(title_) +
         "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n" + body_ + "</body>\n</html>\n";
}

void HtmlPage::write(const std::string& path) const { writeFileAtomically(path, str()); }

}  // namespace roadslam::report
