#include "roadslam/mapping/octo_worker.h"

#include <cmath>

namespace roadslam::mapping {

OctoMapWorker::OctoMapWorker(OctoMapParams params) : builder_(params), thread_([this] { run(); }) {}

OctoMapWorker::~OctoMapWorker() {
  {
    std::lock_guard<std::mutex> lk(m_);
    stop_ = true;
    queue_.clear();
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void OctoMapWorker::push(Item item) {
  {
    std::lock_guard<std::mutex> lk(m_);
    queue_.push_back(std::move(item));
  }
  cv_.notify_one();
}

void OctoMapWorker::rebuild(std::vector<Item> all) {
  {
    std::lock_guard<std::mutex> lk(m_);
    queue_.assign(std::make_move_iterator(all.begin()), std::make_move_iterator(all.end()));
    clear_ = true;
    ++rebuilds_;
  }
  cv_.notify_one();
}

void OctoMapWorker::run() {
  std::unique_lock<std::mutex> lk(m_);
  for (;;) {
    cv_.wait(lk, [this] { return stop_ || clear_ || !queue_.empty(); });
    if (clear_) {  // the tree is only touched by this thread
      builder_.clear();
      inserted_ = 0;
      clear_ = false;
      idle_cv_.notify_all();
    }
    if (queue_.empty()) {
      if (stop_) break;
      continue;
    }
    Item item = std::move(queue_.front());
    queue_.pop_front();
    busy_ = true;
    lk.unlock();
    const double ms = builder_.insert(item.points_lidar, item.T_map_lidar).ms;
    lk.lock();
    busy_ = false;
    total_ms_ += ms;
    ++total_inserts_;
    ++inserted_;
    idle_cv_.notify_all();
  }
  idle_cv_.notify_all();
}

const OctoMapBuilder& OctoMapWorker::finish() {
  {
    std::unique_lock<std::mutex> lk(m_);
    idle_cv_.wait(lk, [this] { return queue_.empty() && !busy_ && !clear_; });
    stop_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
  return builder_;
}

size_t OctoMapWorker::inserted() const {
  std::lock_guard<std::mutex> lk(m_);
  return inserted_;
}
size_t OctoMapWorker::rebuilds() const {
  std::lock_guard<std::mutex> lk(m_);
  return rebuilds_;
}
double OctoMapWorker::meanInsertMs() const {
  std::lock_guard<std::mutex> lk(m_);
  return total_inserts_ ? total_ms_ / total_inserts_ : 0.0;
}

bool takesOctoMap(const std::vector<Keyframe>& kfs, size_t k, double spacing_m) {
  if (k == 0) return true;
  return std::floor(kfs[k].path_m / spacing_m) > std::floor(kfs[k - 1].path_m / spacing_m);
}

std::vector<OctoMapWorker::Item> octoMapItems(const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf,
                                              double spacing_m) {
  std::vector<OctoMapWorker::Item> out;
  for (size_t k = 0; k < kfs.size() && k < T_map_kf.size(); ++k) {
    if (takesOctoMap(kfs, k, spacing_m)) out.push_back({kfs[k].points_lidar, T_map_kf[k]});
  }
  return out;
}

}  // namespace roadslam::mapping
