#include "lang2manip/server/serve_command.hpp"

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <pthread.h>
#include <thread>

#include "lang2manip/cli/run_page.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/core/log.hpp"
#include "lang2manip/server/api_server.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;

bool isLoopback(const std::string& host) { return host == "127.0.0.1" || host == "::1" || host == "localhost"; }

/// SIGINT and SIGTERM, blocked in this thread and so in every thread started after: they wait
/// for serveUntilSignalled() instead of killing the process.
sigset_t blockStopSignals() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  return signals;
}

/// Serves until one of `signals` (blocked by blockStopSignals() before the server's threads
/// started) arrives.
void serveUntilSignalled(ApiServer& server, const sigset_t& signals) {
  std::thread waiter([&server, signals] {
    int received = 0;
    sigwait(&signals, &received);
    server.stop();
  });
  server.serve();
  // serve() also ends when the server fails; wake the waiter so it can be joined.
  pthread_kill(waiter.native_handle(), SIGTERM);
  waiter.join();
}

}  // namespace

void addServeCommand(CLI::App& app, std::ostream& out) {
  auto options = std::make_shared<ServerOptions>();
  auto viewer = std::make_shared<std::string>();
  auto insecure = std::make_shared<bool>(false);
  CLI::App* command = app.add_subcommand(
      "serve", "Serve the HTTP/JSON API (Kautham's session verbs, observe, plan, runs with progress events) and the web viewer");
  command->add_option("PROBLEM", options->defaultProblem, "Problem opened by sessions and runs that name none (default: the paper's scene)");
  command->add_option("--host", options->host, "Address to listen on (loopback unless you say otherwise)")->capture_default_str();
  command->add_option("--port", options->port, "Port (0: any free port, printed)")->capture_default_str();
  command->add_option("--token", options->token, "Require \"Authorization: Bearer TOKEN\" on every request (default: $LANG2MANIP_TOKEN)");
  command->add_option("--data-root", options->dataRoot, "Files named by requests must lie under this directory (default: the current one)");
  command->add_option("--viewer", *viewer, "The viewer's directory (default: the one built beside the program)");
  command->add_option("--max-sessions", options->maxSessions, "Client sessions held at once")->capture_default_str();
  command->add_option("--max-connections", options->maxConnections,
                      "Connections served at once, each by its own thread (more are answered 503)")
      ->capture_default_str();
  command->add_option("--max-request-seconds", options->maxRequestSeconds,
                      "The longest a request's work (a session's solve, a plan) may take; it also stops when its client "
                      "disconnects")
      ->capture_default_str();
  command->add_flag("--insecure", *insecure, "Listen on a non-loopback --host without a token (anyone who reaches it can use it)");
  command->callback([options, viewer, insecure, &out] {
    if (options->token.empty()) {
      if (const char* token = std::getenv("LANG2MANIP_TOKEN")) options->token = token;
    }
    options->viewerDirectory = viewer->empty() ? builtViewerDirectory() : fs::path(*viewer);
    if (!isLoopback(options->host) && options->token.empty()) {
      if (!*insecure) {
        throw InputError("serve: --host " + options->host +
                         " without a token would let anyone who reaches it run tasks, spend the LLM key and read files "
                         "under the data root; give --token TOKEN (or LANG2MANIP_TOKEN), or --insecure to do it anyway");
      }
      logWarning("serve: listening on " + options->host + " without a token (--insecure): anyone who reaches it can use it");
    }
    const sigset_t signals = blockStopSignals();
    ApiServer server(*options);
    out << "lang2manip serving on http://" << options->host << ":" << server.port() << "/ (API at /api, "
        << (options->viewerDirectory.empty() ? "no viewer" : "viewer at /") << "); Ctrl-C stops it" << std::endl;
    serveUntilSignalled(server, signals);
    out << "lang2manip: server stopped" << std::endl;
  });
}

}  // namespace lang2manip
