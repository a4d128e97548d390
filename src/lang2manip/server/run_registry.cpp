#include "lang2manip/server/run_registry.hpp"

#include <algorithm>

#include "lang2manip/core/error.hpp"
#include "lang2manip/server/api_types.hpp"

namespace lang2manip {

/// Where a run is (external linkage: RunRegistry::Run holds one).
enum class RunState { kQueued, kRunning, kSucceeded, kFailed, kCancelled, kError };

namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

const char* stateName(RunState state) {
  switch (state) {
    case RunState::kQueued: return "queued";
    case RunState::kRunning: return "running";
    case RunState::kSucceeded: return "succeeded";
    case RunState::kFailed: return "failed";
    case RunState::kCancelled: return "cancelled";
    case RunState::kError: return "error";
  }
  return "unknown";
}

bool finished(RunState state) { return state != RunState::kQueued && state != RunState::kRunning; }

json progressJson(const ProgressEvent& event) {
  json value{{"type", "progress"}, {"stage", progressStageName(event.stage)}};
  if (event.round > 0) value["round"] = event.round;
  if (event.action >= 0) value["action"] = event.action;
  if (!event.status.empty()) value["status"] = event.status;
  if (!event.text.empty()) value["text"] = event.text;
  return value;
}

}  // namespace

struct RunRegistry::Run {
  std::string id;
  RunRequest request;
  RunState state = RunState::kQueued;
  Clock::time_point created = Clock::now();
  std::vector<json> events;
  std::optional<RunDocuments> documents;
  std::string error;
  /// The problem's name as loaded (the request's may be empty: the default problem).
  std::string problemName;
  CancelFlag cancel = std::make_shared<std::atomic<bool>>(false);
};

RunRegistry::RunRegistry(std::size_t maxQueued, std::size_t maxKept)
    : maxQueued_(maxQueued), maxKept_(maxKept), worker_([this] { work(); }) {}

RunRegistry::~RunRegistry() {
  shutdown();
  if (worker_.joinable()) worker_.join();
}

void RunRegistry::shutdown() {
  const std::lock_guard lock(mutex_);
  stopping_ = true;
  for (auto& [id, run] : runs_) run->cancel->store(true);
  changed_.notify_all();
}

std::string RunRegistry::start(RunRequest request, std::string problemName) {
  const std::lock_guard lock(mutex_);
  if (stopping_) throw ApiError(503, "shutting_down", "the server is shutting down");
  const auto active = std::count_if(runs_.begin(), runs_.end(), [](const auto& entry) { return !finished(entry.second->state); });
  if (static_cast<std::size_t>(active) >= maxQueued_) {
    throw ApiError(429, "too_many_runs", std::to_string(active) + " runs are queued or running, the server's limit; wait for one to finish or cancel one");
  }
  auto run = std::make_shared<Run>();
  run->id = "run-" + std::to_string(nextId_++);
  run->request = std::move(request);
  run->problemName = std::move(problemName);
  runs_[run->id] = run;
  order_.push_back(run->id);
  queue_.push_back(run);
  addEvent(*run, {{"type", "state"}, {"state", "queued"}});
  forgetOldRuns();
  changed_.notify_all();
  return run->id;
}

void RunRegistry::addEvent(Run& run, json event) {
  event["index"] = run.events.size();
  event["time"] = std::chrono::duration<double>(Clock::now() - run.created).count();
  run.events.push_back(std::move(event));
  changed_.notify_all();
}

void RunRegistry::forgetOldRuns() {
  std::size_t kept = order_.size();
  for (auto it = order_.begin(); it != order_.end() && kept > maxKept_;) {
    const auto found = runs_.find(*it);
    if (found != runs_.end() && finished(found->second->state)) {
      runs_.erase(found);
      it = order_.erase(it);
      --kept;
    } else {
      ++it;
    }
  }
}

void RunRegistry::work() {
  std::unique_lock lock(mutex_);
  while (true) {
    changed_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
    if (stopping_) {
      for (const auto& run : queue_) run->state = RunState::kCancelled;
      return;
    }
    const std::shared_ptr<Run> run = queue_.front();
    queue_.pop_front();
    if (run->state != RunState::kQueued) continue;
    run->state = RunState::kRunning;
    addEvent(*run, {{"type", "state"}, {"state", "running"}});
    lock.unlock();
    execute(*run);
    lock.lock();
  }
}

void RunRegistry::execute(Run& run) {
  RunControl control;
  control.stop = StopCondition::onCancel(run.cancel);
  control.seedOmpl = false;
  control.progress = [this, &run](const ProgressEvent& event) {
    const std::lock_guard lock(mutex_);
    addEvent(run, progressJson(event));
  };
  std::optional<RunDocuments> documents;
  std::string error;
  try {
    documents = runTask(run.request, control);
  } catch (const std::exception& exception) {
    error = exception.what();
  }
  const std::lock_guard lock(mutex_);
  if (!error.empty()) {
    run.state = RunState::kError;
    run.error = error;
  } else if (run.cancel->load()) {
    run.state = RunState::kCancelled;
  } else {
    run.state = documents->success ? RunState::kSucceeded : RunState::kFailed;
  }
  run.documents = std::move(documents);
  json event{{"type", "state"}, {"state", stateName(run.state)}};
  if (!error.empty()) event["error"] = error;
  addEvent(run, std::move(event));
  forgetOldRuns();
}

std::shared_ptr<RunRegistry::Run> RunRegistry::find(const std::string& id) const {
  const auto found = runs_.find(id);
  if (found == runs_.end()) throw ApiError(404, "not_found", "no run \"" + id.substr(0, 80) + "\" (finished runs are kept until " + std::to_string(maxKept_) + " newer ones)");
  return found->second;
}

json RunRegistry::status(const std::string& id) const {
  const std::lock_guard lock(mutex_);
  const std::shared_ptr<Run> run = find(id);
  json value{{"id", run->id}, {"state", stateName(run->state)}, {"task", run->request.task},
             {"problem", run->problemName.empty() ? run->request.problem : run->problemName}, {"events", run->events.size()}};
  if (run->documents) value["success"] = run->documents->success;
  if (!run->error.empty()) value["error"] = run->error;
  if (run->documents) value["report"] = run->documents->report;
  return value;
}

json RunRegistry::list() const {
  const std::lock_guard lock(mutex_);
  json runs = json::array();
  for (const std::string& id : order_) {
    const Run& run = *runs_.at(id);
    json value{{"id", run.id}, {"state", stateName(run.state)}, {"task", run.request.task}};
    if (run.documents) value["success"] = run.documents->success;
    runs.push_back(std::move(value));
  }
  return {{"runs", runs}};
}

json RunRegistry::cancel(const std::string& id) {
  const std::lock_guard lock(mutex_);
  const std::shared_ptr<Run> run = find(id);
  if (run->state == RunState::kQueued) {
    run->state = RunState::kCancelled;
    addEvent(*run, {{"type", "state"}, {"state", "cancelled"}});
  } else if (run->state == RunState::kRunning) {
    run->cancel->store(true);
  } else {
    throw ApiError(409, "already_finished", "run " + id + " already ended (" + stateName(run->state) + "): there is nothing to cancel");
  }
  return {{"id", run->id}, {"state", stateName(run->state)}, {"cancel_requested", true}};
}

RunEventBatch RunRegistry::events(const std::string& id, std::size_t from, std::chrono::milliseconds wait) const {
  std::unique_lock lock(mutex_);
  const std::shared_ptr<Run> run = find(id);
  changed_.wait_for(lock, wait, [&] { return stopping_ || run->events.size() > from || finished(run->state); });
  RunEventBatch batch;
  for (std::size_t i = from; i < run->events.size(); ++i) batch.events.push_back(run->events[i]);
  batch.finished = finished(run->state);
  return batch;
}

std::pair<std::string, std::string> RunRegistry::document(const std::string& id, const std::string& name) const {
  static const std::vector<std::string> kNames{"plan.json",        "report.json",     "trajectory.json", "trajectory.csv", "observation.json",
                                               "observation.txt", "prompt.txt",      "viewer.json",     "scene.glb",      "robot_trajectory.json",
                                               "gripper_trajectory.json", "gripper_events.json",
                                               "partial_trajectory.json", "partial_trajectory.csv", "partial_robot_trajectory.json",
                                               "partial_gripper_trajectory.json", "partial_gripper_events.json"};
  if (std::find(kNames.begin(), kNames.end(), name) == kNames.end()) {
    throw ApiError(404, "not_found", "no document \"" + name.substr(0, 80) + "\": a run has plan.json, report.json, trajectory.json, trajectory.csv, observation.json, observation.txt, prompt.txt, viewer.json, scene.glb, robot_trajectory.json, gripper_trajectory.json, gripper_events.json (the motion's documents named partial_... when it did not succeed)");
  }
  const std::lock_guard lock(mutex_);
  const std::shared_ptr<Run> run = find(id);
  if (!finished(run->state)) throw ApiError(409, "not_finished", "run " + id + " is " + stateName(run->state) + "; its documents exist once it has finished");
  if (!run->documents) throw ApiError(404, "not_found", "run " + id + " ended without documents: " + run->error);
  const RunDocuments& documents = *run->documents;
  const auto text = [](const json& value) { return value.dump(2) + "\n"; };
  if (name == "report.json") return {"application/json", text(documents.report)};
  if (name == "observation.json") return {"application/json", text(documents.observation)};
  if (name == "observation.txt") return {"text/plain; charset=utf-8", documents.observationText};
  if (name == "prompt.txt") return {"text/plain; charset=utf-8", documents.prompt};
  if (name == "viewer.json") return {"application/json", text(documents.viewerDocument)};
  if (name == "scene.glb") return {"model/gltf-binary", documents.sceneGlb};
  if (name == "plan.json" && documents.plan) return {"application/json", text(*documents.plan)};
  for (const auto& [file, content] : motionDocuments(documents)) {
    const std::string type = file.ends_with(".csv") ? "text/csv" : "application/json";
    if (name == trajectoryDocumentName(file, documents.success)) return {type, content};
    if (name == file) throw ApiError(404, "not_found", "run " + id + " did not succeed: what it executed is partial_" + name + ", not " + name);
  }
  throw ApiError(404, "not_found", "run " + id + " produced no " + name + " (no plan reached that stage)");
}

}  // namespace lang2manip
