#pragma once
/// @file Progress of long work (a task run) as structured events: the repair loop reports each
/// planner call and its outcome, the executor each action, so that a caller can show or stream
/// them (the server sends them as server-sent events). Sinks are called on the worker's thread,
/// synchronously: they must be quick and must not throw.

#include <functional>
#include <string>

namespace lang2manip {

enum class ProgressStage {
  kObserve,         ///< the environment is being observed
  kPlannerCall,     ///< a task planner is asked (round)
  kPlannerAnswer,   ///< its answer was checked (round, status = the round's outcome, text = why)
  kActionStarted,   ///< an action is grounded and executed (action, text = the action)
  kActionFinished,  ///< it ended (action, status = its status, text = the choice or the reason)
  kVerify,          ///< the final world is checked against the goals
};

/// "observe", "planner_call", "planner_answer", "action_started", "action_finished", "verify".
std::string progressStageName(ProgressStage stage);

struct ProgressEvent {
  ProgressStage stage = ProgressStage::kObserve;
  /// Repair round (from 1) of planner events; 0 otherwise.
  int round = 0;
  /// Index of the action in its plan (from 0) of action events; -1 otherwise.
  int action = -1;
  /// The round's outcome or the action's status ("accepted", "succeeded", "failed", ...).
  std::string status;
  /// For people: the action, the choice made, or why it failed.
  std::string text;
};

/// Receives progress events; an empty function receives nothing.
using ProgressSink = std::function<void(const ProgressEvent&)>;

/// Calls `sink` when it is set.
inline void report(const ProgressSink& sink, const ProgressEvent& event) {
  if (sink) sink(event);
}

}  // namespace lang2manip
