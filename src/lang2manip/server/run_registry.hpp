#pragma once
/// @file The server's task runs: queued, executed one after another on a worker thread (runs
/// are CPU-bound and OMPL's random seed is process-wide), watched through their progress events,
/// cancelled on request, and kept (documents and events) until too many have finished.

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "lang2manip/cli/task_run.hpp"

namespace lang2manip {

/// Events of a run from some index on.
struct RunEventBatch {
  std::vector<nlohmann::json> events;
  /// True when the run has ended and `events` reaches its last event.
  bool finished = false;
};

class RunRegistry {
 public:
  RunRegistry(std::size_t maxQueued, std::size_t maxKept);
  /// Cancels every run and waits for the worker.
  ~RunRegistry();
  RunRegistry(const RunRegistry&) = delete;
  RunRegistry& operator=(const RunRegistry&) = delete;

  /// Queues `request` (its problem shown as `problemName` in its status); its id. Throws
  /// ApiError 429 when maxQueued runs wait or run.
  std::string start(RunRequest request, std::string problemName = "");
  /// {"id", "state", "task", "problem", "created", "success", "error", "events"}; 404 for an unknown id.
  [[nodiscard]] nlohmann::json status(const std::string& id) const;
  /// Every run kept, oldest first (status without events).
  [[nodiscard]] nlohmann::json list() const;
  /// Cancels a queued or running run; 404 for an unknown id, 409 for a run that already ended.
  nlohmann::json cancel(const std::string& id);
  /// Events from index `from`, waiting up to `wait` when there is none yet. 404 for an unknown id.
  RunEventBatch events(const std::string& id, std::size_t from, std::chrono::milliseconds wait) const;
  /// A document of a finished run: plan.json, report.json, trajectory.json, trajectory.csv,
  /// observation.json, observation.txt, prompt.txt, viewer.json, scene.glb (the viewer's). 404 for an unknown run or name, 409 while the
  /// run has not finished, 404 when the run did not produce it.
  [[nodiscard]] std::pair<std::string, std::string> document(const std::string& id, const std::string& name) const;
  /// Cancels every run; start() refuses afterwards.
  void shutdown();

 private:
  struct Run;
  [[nodiscard]] std::shared_ptr<Run> find(const std::string& id) const;
  void work();
  void execute(Run& run);
  void addEvent(Run& run, nlohmann::json event);
  void forgetOldRuns();

  std::size_t maxQueued_;
  std::size_t maxKept_;
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::map<std::string, std::shared_ptr<Run>> runs_;
  std::vector<std::string> order_;
  std::deque<std::shared_ptr<Run>> queue_;
  long nextId_ = 1;
  bool stopping_ = false;
  std::thread worker_;
};

}  // namespace lang2manip
