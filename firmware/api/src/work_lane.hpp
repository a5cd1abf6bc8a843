#pragma once

// WorkLane: a few threads and a bounded queue. Work past the queue's bound is refused at once
// (the caller answers 503) rather than queued without end: a flood of requests costs the
// flood, not the memory of the controller.
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace tilejet::api {

class WorkLane {
  public:
    WorkLane(int threads, std::size_t max_queued);
    // Runs what is queued, then joins; later submits are refused.
    void close();
    ~WorkLane() { close(); }
    WorkLane(const WorkLane&) = delete;
    WorkLane& operator=(const WorkLane&) = delete;

    // False when max_queued tasks already wait: the task is not taken.
    bool submit(std::function<void()> task);

  private:
    void run();
    const std::size_t max_queued_;
    std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<std::function<void()>> queue_;
    bool stopping_ = false;
    std::vector<std::thread> threads_;
};

}  // namespace tilejet::api
