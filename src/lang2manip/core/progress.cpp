#include "lang2manip/core/progress.hpp"

namespace lang2manip {

std::string progressStageName(ProgressStage stage) {
  switch (stage) {
    case ProgressStage::kObserve: return "observe";
    case ProgressStage::kPlannerCall: return "planner_call";
    case ProgressStage::kPlannerAnswer: return "planner_answer";
    case ProgressStage::kActionStarted: return "action_started";
    case ProgressStage::kActionFinished: return "action_finished";
    case ProgressStage::kVerify: return "verify";
  }
  return "unknown";
}

}  // namespace lang2manip
