#include "roadslam/rawlog/rawlog_session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <regex>
#include <stdexcept>
#include <thread>

namespace roadslam::rawlog {
namespace fs = std::filesystem;

std::vector<std::string> RawlogSession::segmentsOf(const std::string& folder) {
  static const std::regex name(R"((.+)_([0-9]+)\.rawlog)");
  std::vector<std::pair<std::string, std::string>> found;  // (prefix, file name)
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(folder, ec)) {
    std::smatch m;
    const std::string f = e.path().filename().string();
    if (e.is_regular_file() && std::regex_match(f, m, name)) found.emplace_back(m[1].str(), f);
  }
  if (found.empty()) return {};
  std::sort(found.begin(), found.end());  // zero-padded numbers sort as numbers
  const std::string prefix = found.front().first;
  std::vector<std::string> out;
  for (const auto& [p, f] : found)
    if (p == prefix) out.push_back((fs::path(folder) / f).string());
  return out;
}

std::unique_ptr<RawlogSession> RawlogSession::open(const std::vector<std::string>& segments,
                                                   const RawlogIndexOptions& options) {
  if (segments.empty()) throw std::runtime_error("a rawlog session needs at least one segment");
  std::unique_ptr<RawlogSession> s(new RawlogSession());
  for (const auto& path : segments) {
    s->parts_.push_back(BackgroundRawlogIndex::open(path, options));
    std::error_code ec;
    s->sizes_.push_back(std::max<uint64_t>(1, fs::file_size(path, ec)));
  }
  s->poll();
  return s;
}

RawlogSession::~RawlogSession() = default;

std::size_t RawlogSession::poll() {
  const std::size_t before = entries_.size();
  for (auto& p : parts_) p->poll();
  while (shown_ < parts_.size()) {
    BackgroundRawlogIndex& part = *parts_[shown_];
    for (; taken_ < part.size(); ++taken_) {
      RawlogEntry e = part.entry(taken_);
      e.label = labels_.id(part.label(taken_));
      e.cls = classes_.id(part.className(taken_));
      const auto i = uint32_t(entries_.size());
      entries_.push_back(e);
      where_.emplace_back(uint32_t(shown_), uint32_t(taken_));
      time_.add(i, e.stamp_s);
    }
    if (!part.done() && part.error().empty()) break;  // the next segment waits for this one
    ++shown_;
    taken_ = 0;
  }
  return entries_.size() - before;
}

void RawlogSession::waitUntilDone() {
  while (!done()) {
    poll();
    if (!done()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

double RawlogSession::progress() const {
  uint64_t total = 0;
  double read = 0;
  for (std::size_t k = 0; k < parts_.size(); ++k) {
    total += sizes_[k];
    read += parts_[k]->progress() * double(sizes_[k]);
  }
  return read / double(std::max<uint64_t>(1, total));
}

std::vector<std::string> RawlogSession::errors() const {
  std::vector<std::string> out;
  for (const auto& p : parts_)
    if (!p->error().empty()) out.push_back(p->error());
  return out;
}

std::shared_ptr<mrpt::obs::CObservation> RawlogSession::load(std::size_t i) {
  const auto [seg, local] = where_.at(i);
  return parts_[seg]->load(local);
}

}  // namespace roadslam::rawlog
