// Task runs over HTTP: queued, streamed as server-sent events, cancelled, their documents; observe
// and plan; clients that go away.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "server/api_test_server.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;
using test::ApiTestServer;
using test::bodyOf;
using test::errorOf;
using ::testing::HasSubstr;

/// The events of a run's stream, read to its end.
std::vector<json> streamedEvents(const ApiTestServer& server, const std::string& id) {
  std::string text;
  httplib::Client client = server.client();
  const auto result = client.Get(("/api/runs/" + id + "/events").c_str(), [&](const char* data, std::size_t size) {
    text.append(data, size);
    return true;
  });
  EXPECT_TRUE(result);
  std::vector<json> events;
  for (std::size_t at = text.find("data: "); at != std::string::npos; at = text.find("data: ", at + 1)) {
    events.push_back(json::parse(text.substr(at + 6, text.find('\n', at) - at - 6)));
  }
  return events;
}

bool hasEvent(const std::vector<json>& events, const std::string& key, const std::string& value) {
  return std::any_of(events.begin(), events.end(), [&](const json& event) { return event.value(key, "") == value; });
}

TEST(ApiRuns, ARunStreamsItsProgressAndKeepsItsDocuments) {
  ApiTestServer server;
  const auto started = server.postJson("/api/runs", {{"task", "put the marker in the holder"}, {"seed", 3}});
  ASSERT_EQ(started->status, 202) << started->body;
  const std::string id = bodyOf(started)["id"];
  const std::vector<json> events = streamedEvents(server, id);
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.front()["state"], "queued");
  EXPECT_EQ(events.back()["state"], "succeeded") << events.back().dump();
  EXPECT_TRUE(hasEvent(events, "stage", "observe"));
  EXPECT_TRUE(hasEvent(events, "stage", "planner_call"));
  EXPECT_TRUE(hasEvent(events, "stage", "action_started"));
  EXPECT_TRUE(hasEvent(events, "stage", "verify"));
  for (std::size_t i = 0; i < events.size(); ++i) EXPECT_EQ(events[i]["index"], i);

  const json status = bodyOf(server.get("/api/runs/" + id));
  EXPECT_EQ(status["state"], "succeeded");
  EXPECT_EQ(status["problem"], "panda_desk") << "the default problem, by name";
  EXPECT_TRUE(status["report"]["success"].get<bool>());
  const json plan = bodyOf(server.get("/api/runs/" + id + "/files/plan.json"));
  EXPECT_EQ(plan["actions"].size(), 2U);
  const auto csv = server.get("/api/runs/" + id + "/files/trajectory.csv");
  EXPECT_EQ(csv->get_header_value("Content-Type"), "text/csv");
  EXPECT_EQ(server.get("/api/runs/" + id + "/files/secrets.txt")->status, 404);
  EXPECT_EQ(server.get("/api/runs/run-999")->status, 404);
  EXPECT_EQ(server.get("/api/runs/run-999/events")->status, 404);
  EXPECT_EQ(bodyOf(server.get("/api/runs"))["runs"].size(), 1U);

  // Resuming after the last event seen gives nothing new.
  httplib::Client client = server.client();
  const auto resumed = client.Get(("/api/runs/" + id + "/events").c_str(), {{"Last-Event-ID", std::to_string(events.size() - 1)}});
  EXPECT_THAT(resumed->body, ::testing::Not(HasSubstr("data: ")));
}

TEST(ApiRuns, AFailedRunServesItsMotionOnlyUnderPartialNames) {
  ApiTestServer server;
  const auto started = server.postJson("/api/runs", {{"task", "put the eraser 300 cm to the left of the holder"}, {"rounds", 1}});
  ASSERT_EQ(started->status, 202) << started->body;
  const std::string id = bodyOf(started)["id"];
  const std::vector<json> events = streamedEvents(server, id);
  ASSERT_FALSE(events.empty());
  ASSERT_EQ(events.back()["state"], "failed") << events.back().dump();
  const std::string files = "/api/runs/" + id + "/files/";
  for (const char* name : {"trajectory.json", "trajectory.csv", "robot_trajectory.json"}) {
    const auto refused = server.get(files + name);
    EXPECT_EQ(refused->status, 404) << name;
    EXPECT_THAT(refused->body, HasSubstr("did not succeed: what it executed is partial_" + std::string(name))) << refused->body;
    EXPECT_EQ(server.get(files + "partial_" + name)->status, 200) << name;
  }
  EXPECT_EQ(bodyOf(server.get(files + "partial_trajectory.json"))["segments"].size(), 1U);
  EXPECT_FALSE(bodyOf(server.get(files + "report.json"))["success"].get<bool>());
}

TEST(ApiRuns, QueuedAndRunningRunsCanBeCancelled) {
  ApiTestServer server;
  const std::string first = bodyOf(server.postJson("/api/runs", json::object()))["id"];
  const std::string second = bodyOf(server.postJson("/api/runs", json::object()))["id"];
  const auto cancelled = server.post("/api/runs/" + second + "/cancel");
  EXPECT_EQ(cancelled->status, 202);
  ASSERT_EQ(server.post("/api/runs/" + first + "/cancel")->status, 202);
  const std::vector<json> firstEvents = streamedEvents(server, first);
  EXPECT_EQ(firstEvents.back()["state"], "cancelled") << firstEvents.back().dump();
  EXPECT_EQ(bodyOf(server.get("/api/runs/" + first))["state"], "cancelled");
  EXPECT_EQ(bodyOf(server.get("/api/runs/" + second))["state"], "cancelled");
  // An ended run has nothing to cancel.
  for (const std::string& ended : {first, second}) {
    const auto again = server.post("/api/runs/" + ended + "/cancel");
    EXPECT_EQ(again->status, 409) << again->body;
    EXPECT_EQ(bodyOf(again)["error"]["code"], "already_finished");
    EXPECT_THAT(errorOf(again), HasSubstr("already ended (cancelled)"));
  }
  const auto early = server.get("/api/runs/" + second + "/files/report.json");
  EXPECT_EQ(early->status, 404);
}

TEST(ApiRuns, BadRunRequestsAreRefusedBeforeQueueing) {
  ServerOptions options;
  options.maxQueuedRuns = 1;
  ApiTestServer server(options);
  const auto empty = server.postJson("/api/runs", {{"task", "  "}});
  EXPECT_EQ(empty->status, 400);
  EXPECT_THAT(errorOf(empty), HasSubstr("\"task\""));
  const auto rounds = server.postJson("/api/runs", {{"rounds", 0}});
  EXPECT_EQ(rounds->status, 400);
  EXPECT_THAT(errorOf(rounds), HasSubstr("\"rounds\""));
  const auto llm = server.postJson("/api/runs", {{"llm", "nosuch:model"}});
  EXPECT_EQ(llm->status, 400);
  EXPECT_THAT(errorOf(llm), HasSubstr("nosuch"));
  const auto field = server.postJson("/api/runs", {{"llm_base_url", "http://169.254.169.254/"}});
  EXPECT_EQ(field->status, 400);
  const auto scaling = server.postJson("/api/runs", {{"velocity_scaling", 1.5}});
  EXPECT_EQ(scaling->status, 400);
  EXPECT_THAT(errorOf(scaling), HasSubstr("\"velocity_scaling\""));
  const auto acceleration = server.postJson("/api/runs", {{"acceleration_scaling", 0}});
  EXPECT_EQ(acceleration->status, 400);
  EXPECT_THAT(errorOf(acceleration), HasSubstr("\"acceleration_scaling\""));
  // Names the run would refuse only once it started: refused now, with the valid names.
  const auto planner = server.postJson("/api/runs", {{"planner", "NotAPlanner"}});
  EXPECT_EQ(planner->status, 400);
  EXPECT_THAT(errorOf(planner), HasSubstr("body field \"planner\""));
  EXPECT_THAT(errorOf(planner), HasSubstr("RRTConnect"));
  const auto ik = server.postJson("/api/runs", {{"ik", "magic"}});
  EXPECT_EQ(ik->status, 400);
  EXPECT_THAT(errorOf(ik), HasSubstr("body field \"ik\""));
  EXPECT_THAT(errorOf(ik), HasSubstr("dls"));
  const auto arm = server.postJson("/api/runs", {{"arm", "tentacle"}});
  EXPECT_EQ(arm->status, 400);
  EXPECT_THAT(errorOf(arm), HasSubstr("body field \"arm\""));
  EXPECT_THAT(errorOf(arm), HasSubstr("tentacle"));
  const auto problem = server.postJson("/api/runs", {{"problem", "nosuch.xml"}});
  EXPECT_EQ(problem->status, 404);
  EXPECT_EQ(bodyOf(server.get("/api/runs"))["runs"].size(), 0U) << "nothing was queued";
  const auto timing = server.postJson("/api/runs", {{"timing", "fastest"}});
  EXPECT_EQ(timing->status, 400);
  EXPECT_THAT(errorOf(timing), HasSubstr("rest-to-rest"));
  ASSERT_EQ(server.postJson("/api/runs", json::object())->status, 202);
  const auto full = server.postJson("/api/runs", json::object());
  EXPECT_EQ(full->status, 429);
  EXPECT_THAT(errorOf(full), HasSubstr("limit"));
}

TEST(ApiRuns, AClientLeavingTheStreamDoesNotStopTheRunOrTheServer) {
  ApiTestServer server;
  const std::string id = bodyOf(server.postJson("/api/runs", json::object()))["id"];
  {
    httplib::Client client = server.client();
    std::atomic<int> chunks{0};
    const auto result = client.Get(("/api/runs/" + id + "/events").c_str(), [&](const char*, std::size_t) { return ++chunks < 2; });
    EXPECT_FALSE(result) << "the client stopped reading";
  }
  EXPECT_EQ(server.get("/api/health")->status, 200);
  const std::vector<json> events = streamedEvents(server, id);
  EXPECT_EQ(events.back()["state"], "succeeded");
  const auto late = server.post("/api/runs/" + id + "/cancel");
  EXPECT_EQ(late->status, 409);
  EXPECT_THAT(errorOf(late), HasSubstr("already ended (succeeded)"));
}

TEST(ApiRuns, EventStreamsAreCappedSoOtherRequestsAreServed) {
  ServerOptions options;
  options.maxConnections = 6;
  options.maxEventStreams = 100;  // eventStreamLimit() keeps half of the connections for the rest
  ASSERT_EQ(eventStreamLimit(options), 3U);
  ApiTestServer server(options);
  // The second run waits behind the first: its streams stay open.
  const std::string first = bodyOf(server.postJson("/api/runs", json::object()))["id"];
  const std::string id = bodyOf(server.postJson("/api/runs", json::object()))["id"];
  std::atomic<bool> leave{false};
  std::atomic<int> reading{0};
  std::vector<std::thread> watchers;
  for (int i = 0; i < 3; ++i) {
    watchers.emplace_back([&] {
      httplib::Client client = server.client();
      bool counted = false;
      (void)client.Get(("/api/runs/" + id + "/events").c_str(), [&](const char*, std::size_t) {
        if (!counted) ++reading;
        counted = true;
        return !leave.load();
      });
    });
  }
  for (int i = 0; i < 500 && reading.load() < 3; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_EQ(reading.load(), 3);
  const auto refused = server.get("/api/runs/" + id + "/events");
  EXPECT_EQ(refused->status, 503);
  EXPECT_EQ(refused->get_header_value("Retry-After"), "5");
  EXPECT_THAT(errorOf(refused), HasSubstr("limit of 3 event streams"));
  const auto started = std::chrono::steady_clock::now();
  for (int i = 0; i < 3; ++i) EXPECT_EQ(server.get("/api/health")->status, 200);
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(1));
  leave = true;
  for (std::thread& watcher : watchers) watcher.join();
  for (const std::string& run : {first, id}) (void)server.post("/api/runs/" + run + "/cancel");
  // The slots are given back when the streams end.
  for (int i = 0; i < 100 && server.get("/api/runs/" + id + "/events")->status == 503; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(server.get("/api/runs/" + id + "/events")->status, 200);
}

TEST(ApiTasks, ObserveAndPlan) {
  ApiTestServer server;
  const json observed = bodyOf(server.postJson("/api/observe", {{"problem", "panda_desk"}}));
  EXPECT_THAT(observed["text"].get<std::string>(), HasSubstr("marker"));
  const json planned = bodyOf(server.postJson("/api/plan", {{"task", "put the marker and eraser in the holder"}}));
  EXPECT_TRUE(planned["success"].get<bool>()) << planned.dump();
  EXPECT_EQ(planned["plan"]["actions"].size(), 4U);
  const json refused = bodyOf(server.postJson("/api/plan", {{"task", "put the unicorn in the holder"}}));
  EXPECT_FALSE(refused["success"].get<bool>());
  EXPECT_THAT(refused["failure"].get<std::string>(), HasSubstr("unicorn"));
  EXPECT_EQ(server.postJson("/api/plan", json::object())->status, 400);
}

}  // namespace
}  // namespace lang2manip
