#pragma once
/// \file bounded_queue.h
/// Fixed-capacity FIFO between one receiving thread and the writer thread. A full queue never
/// blocks the producer: tryPush() refuses the item and the producer counts it as dropped, so a
/// disk that cannot keep up shows up as counted drops instead of a stalled socket (whose kernel
/// buffer would then overflow silently).

#include <cstddef>
#include <deque>
#include <mutex>
#include <utility>

namespace roadslam::grabber {

template <typename T>
class BoundedQueue {
 public:
  explicit BoundedQueue(std::size_t capacity) : capacity_(capacity) {}

  /// Appends \p item unless the queue holds capacity() items; returns false (item untouched) then.
  bool tryPush(T&& item) {
    std::lock_guard<std::mutex> lock(m_);
    if (q_.size() >= capacity_) return false;
    q_.push_back(std::move(item));
    if (q_.size() > high_water_) high_water_ = q_.size();
    return true;
  }
  /// Moves the oldest item into \p out; false when empty.
  bool tryPop(T& out) {
    std::lock_guard<std::mutex> lock(m_);
    if (q_.empty()) return false;
    out = std::move(q_.front());
    q_.pop_front();
    return true;
  }
  std::size_t size() const {
    std::lock_guard<std::mutex> lock(m_);
    return q_.size();
  }
  /// Largest size() ever reached [items].
  std::size_t highWater() const {
    std::lock_guard<std::mutex> lock(m_);
    return high_water_;
  }
  std::size_t capacity() const { return capacity_; }

 private:
  mutable std::mutex m_;
  std::deque<T> q_;
  std::size_t capacity_;
  std::size_t high_water_ = 0;
};

}  // namespace roadslam::grabber
