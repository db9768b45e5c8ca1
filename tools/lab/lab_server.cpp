#include "lab/lab_server.hpp"

#include <atomic>
#include <cctype>
#include <charconv>
#include <chrono>
#include <csignal>
#include <cstring>
#include <functional>
#include <iostream>
#include <thread>

#include <httplib.h>
#include <pthread.h>
#include <nlohmann/json.hpp>

#include "illum/core/error.hpp"
#include "lab/lab_assets.hpp"
#include "lab/lab_compare.hpp"
#include "lab/lab_hierarchy.hpp"
#include "lab/lab_radiosity.hpp"
#include "lab/lab_reference.hpp"
#include "lab/lab_trace.hpp"

#ifndef ILLUM_LAB_EXERCISES
#define ILLUM_LAB_EXERCISES ""
#endif

namespace illum::lab {

bool lab_available() { return true; }

namespace {

using nlohmann::json;

Params params_of(const httplib::Request& request) {
  return checked_params(request.target, Params(request.params.begin(), request.params.end()));
}

void send_json(httplib::Response& response, int status, const std::string& body) {
  response.status = status;
  response.set_content(body, "application/json; charset=utf-8");
}

// Every endpoint's body runs here: whatever it throws becomes an answer with
// a status and a message, never a crash of the server.
template <class Body>
void guarded(httplib::Response& response, Body body) {
  try {
    body();
  } catch (const BadRequest& e) {
    send_json(response, 400, error_json(e.what()));
  } catch (const NotFound& e) {
    send_json(response, 404, error_json(e.what()));
  } catch (const InputError& e) {  // a scene file the lab loads on demand
    send_json(response, 400, error_json(e.what()));
  } catch (const std::invalid_argument& e) {  // the library refuses what the request asked for
    send_json(response, 400, error_json(e.what()));
  } catch (const Cancelled& e) {  // Ctrl-C, or a newer request of the same kind: nobody waits for it
    send_json(response, lab_stopping() ? 503 : 409,
              json{{"error", e.what()}, {"cancelled", true}}.dump() + "\n");
  } catch (const NotImplemented& e) {  // a stub of the student edition
    send_json(
        response, 501,
        json{{"error", e.message()}, {"not_implemented", e.exercise()}, {"hint", e.hint()}}.dump() + "\n");
  } catch (const std::exception& e) {
    std::cerr << "illum lab: error: " << e.what() << "\n";
    send_json(response, 500, error_json(std::string("the lab failed: ") + e.what()));
  } catch (...) {
    std::cerr << "illum lab: error: an unknown exception\n";
    send_json(response, 500, error_json("the lab failed with an unknown exception"));
  }
}

// SIGINT and SIGTERM are blocked in every thread (from the start of run_lab,
// so that every thread made afterwards, OpenMP's included, inherits the
// mask) and taken by one that waits for them, so that the server is stopped
// from ordinary code rather than from a signal handler; a second signal
// while stopping ends the process at once.
class SignalWaiter {
 public:
  SignalWaiter() {
    sigemptyset(&set_);
    sigaddset(&set_, SIGINT);
    sigaddset(&set_, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &set_, nullptr);
  }
  ~SignalWaiter() {
    done_ = true;
    if (thread_.joinable()) thread_.join();
    pthread_sigmask(SIG_UNBLOCK, &set_, nullptr);
  }
  // On the first signal: every long request stops (stop_all_work), then `stopping` (the reference
  // lab) and the server.
  void start(httplib::Server& server, std::function<void()> stopping) {
    thread_ = std::thread([this, &server, stopping] { wait(server, stopping); });
  }
  int signal() const { return signal_; }

 private:
  void wait(httplib::Server& server, const std::function<void()>& stopping) {
    const timespec step{0, 50'000'000};
    std::chrono::steady_clock::time_point asked;
    while (!done_) {
      const int s = sigtimedwait(&set_, nullptr, &step);
      if (s <= 0) {
        // A worker waiting out an idle connection's keep-alive (up to a second) would hold the
        // end: the lab keeps nothing to save, so 0.4 s after the signal it just ends.
        if (signal_ != 0 && std::chrono::steady_clock::now() - asked > std::chrono::milliseconds(400)) {
          std::cerr << "illum lab: stopped" << std::endl;
          std::_Exit(0);
        }
        continue;
      }
      if (signal_ != 0) std::_Exit(128 + s);  // a second Ctrl-C: do not wait for the workers
      signal_ = s;
      asked = std::chrono::steady_clock::now();
      std::cerr << "illum lab: " << (s == SIGINT ? "SIGINT" : "SIGTERM") << ": stopping\n";
      stop_all_work();
      stopping();
      server.stop();
    }
  }

  sigset_t set_;
  std::atomic<bool> done_{false};
  std::atomic<int> signal_{0};
  std::thread thread_;
};

// The page names its tab (and view) in this header, so that a newer request of the same kind from
// the same place stops the one still running (Work); other clients send none.
constexpr const char* tab_header = "X-Lab-Tab";

std::string tab_of(const httplib::Request& request) {
  const std::string tab = request.get_header_value(tab_header);
  if (tab.size() > 64) throw BadRequest(std::string("header ") + tab_header + " is longer than 64 bytes");
  for (const char c : tab)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || std::strchr("/_-", c)))
      throw BadRequest(std::string("header ") + tab_header +
                       " holds a character other than letters, digits and /_-");
  return tab;
}

std::string number_text(double v) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
  return std::string(buffer, end);
}

// The command line of the reference lab: this one's scene and settings (its own free port).
std::vector<std::string> reference_arguments(const LabOptions& o) {
  std::vector<std::string> a{o.scene,
                             "--source",
                             o.source.string(),
                             "--depth",
                             std::to_string(o.settings.max_depth),
                             "--prune",
                             number_text(o.settings.min_contribution)};
  // The default OUT (SOURCE/out) may not be there yet: the reference lab would refuse it.
  if (std::error_code e; std::filesystem::is_directory(o.out, e))
    a.insert(a.end(), {"--out", o.out.string()});
  if (o.settings.width > 0) a.insert(a.end(), {"--width", std::to_string(o.settings.width)});
  if (o.settings.height > 0) a.insert(a.end(), {"--height", std::to_string(o.settings.height)});
  if (!o.settings.use_plan) a.push_back("--no-plan");
  return a;
}

}  // namespace

int run_lab(const LabOptions& options) {
  std::signal(SIGPIPE, SIG_IGN);  // a tab closed mid-answer must not end the server
  SignalWaiter signals;
  const std::vector<SceneEntry> catalogue = scene_catalogue(options.scene);
  TraceLab trace(catalogue, options.settings);  // loads the scene: a bad one stops here
  RadiosityLab radiosity(catalogue);
  HierarchyLab hierarchy(catalogue);
  const CompareLab compare(options.source, options.out);
  ReferenceLab reference(options.reference, reference_arguments(options));
  if (!options.reference.empty() && !reference.available()) {
    if (options.reference_required) throw std::runtime_error("--reference: " + reference.why());
    std::cerr << "illum lab: no reference to compare with: " << reference.why() << "\n";
  }

  httplib::Server server;
  // One worker per connection, up to 64 (a browser keeps 6 connections to the lab): a client that
  // sends half a request holds one of them for the read timeout below, not the lab.
  server.new_task_queue = [] { return new httplib::ThreadPool(64); };
  server.set_keep_alive_timeout(1);  // an idle tab's connection does not hold a worker
  server.set_keep_alive_max_count(100);
  // Every read and write of a connection must progress within these: a client that stops sending
  // (half-open) or sends a header line every few seconds is dropped after 2 s of silence.
  server.set_read_timeout(2);
  server.set_write_timeout(10);
  server.set_payload_max_length(64 * 1024);
  // Headers and body go out in separate writes: without TCP_NODELAY, Nagle's algorithm holds the
  // body back until the browser's delayed ACK, some 40 ms per request.
  server.set_tcp_nodelay(true);
  // SO_REUSEADDR only: httplib's default adds SO_REUSEPORT, with which a second lab could listen on
  // the same port and take half of the first one's requests.
  server.set_socket_options([](socket_t socket) {
    const int yes = 1;
    setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });

  int port = options.port;
  if (port < 0 || port > 65535) throw std::invalid_argument("--port must lie in 0 … 65535");
  if (port == 0) {
    port = server.bind_to_any_port("127.0.0.1");
    if (port <= 0) throw std::runtime_error("cannot listen on 127.0.0.1 on any port");
  } else if (!server.bind_to_port("127.0.0.1", port)) {
    throw std::runtime_error(
        "cannot listen on 127.0.0.1:" + std::to_string(port) +
        " (is another `illum lab` running there?): choose another port with --port N, or "
        "--port 0 for any free one");
  }
  const std::string host = "127.0.0.1:" + std::to_string(port), local = "localhost:" + std::to_string(port);

  // Only this machine's browser, by name: a page elsewhere that resolves its
  // own host name to 127.0.0.1 (DNS rebinding) sends another Host and is refused.
  server.set_pre_routing_handler([&](const httplib::Request& request, httplib::Response& response) {
    const std::string h = request.get_header_value("Host");
    if (h != host && h != local) {
      send_json(response, 403, error_json("the lab answers requests to " + host + " or " + local + " only"));
      return httplib::Server::HandlerResponse::Handled;
    }
    try {
      tab_of(request);
    } catch (const BadRequest& e) {
      send_json(response, 400, error_json(e.what()));
      return httplib::Server::HandlerResponse::Handled;
    }
    if (request.method != "GET" && request.method != "HEAD") {
      response.set_header("Allow", "GET, HEAD");
      send_json(response, 405, error_json("the lab answers GET requests only, not " + request.method));
      return httplib::Server::HandlerResponse::Handled;
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });
  server.set_post_routing_handler([](const httplib::Request& request, httplib::Response& response) {
    response.set_header("X-Content-Type-Options", "nosniff");
    // The page loads nothing from anywhere but the lab itself.
    response.set_header("Content-Security-Policy",
                        "default-src 'self'; img-src 'self' blob: data:; style-src 'self' 'unsafe-inline'");
    response.set_header("Cache-Control", request.path.rfind("/api/", 0) == 0 ? "no-store" : "no-cache");
  });
  server.set_error_handler([](const httplib::Request& request, httplib::Response& response) {
    if (!response.body.empty()) return;  // an endpoint's own answer
    if (response.status == 404)
      send_json(response, 404,
                error_json("no such page or endpoint: " + request.path + " (see docs/lab.md)"));
  });

  for (const LabAsset& asset : lab_assets()) {
    const LabAsset* a = &asset;
    server.Get(std::string(asset.path), [a](const httplib::Request&, httplib::Response& response) {
      response.set_content(a->data, std::string(a->content_type));
    });
  }
  server.Get("/api/info", [&](const httplib::Request& request, httplib::Response& response) {
    guarded(response, [&] {
      const Query q(params_of(request), {});
      json scenes = json::array();
      for (const SceneEntry& e : catalogue) scenes.push_back(e.id);
      std::error_code ec;
      send_json(
          response, 200,
          json{{"version", "illum 0.1.0"},
               {"scene", trace.default_scene()},
               {"scenes", scenes},
               {"settings", json::parse(trace.settings_json())},
               {"exercises", ILLUM_LAB_EXERCISES},
               {"student_edition", std::filesystem::exists(options.source / "STUDENT_EDITION", ec)},
               {"three", lab_has_three()},
               {"port", port},
               {"reference",
                {{"available", reference.available()},
                 {"program", options.reference.empty() ? json(nullptr) : json(options.reference.string())},
                 {"why", reference.available() ? "" : reference.why()}}}}
                  .dump() +
              "\n");
    });
  });
  // Each endpoint's work is keyed by its path and the page's tab: the tab's next request of the
  // same kind stops it (a session's steps are keyed by the session instead, in step_json).
  const auto text_endpoint = [&](const char* path, auto method, const char* type) {
    server.Get(path, [&, path, method, type](const httplib::Request& request, httplib::Response& response) {
      guarded(response, [&] {
        const std::string tab = tab_of(request);
        const Work work(tab.empty() ? "" : std::string(path) + "|" + tab);
        response.status = 200;
        response.set_content(method(params_of(request), work), type);
      });
    });
  };
  const char* json_type = "application/json; charset=utf-8";
  using P = const Params&;
  using W = const Work&;
  text_endpoint(
      "/api/scene", [&](P p, W) { return trace.geometry_json(p); }, json_type);
  text_endpoint(
      "/api/render", [&](P p, W w) { return trace.render_png(p, w); }, "image/png");
  text_endpoint(
      "/api/trace", [&](P p, W) { return trace.trace_json(p); }, json_type);
  text_endpoint(
      "/api/radiosity/mesh", [&](P p, W w) { return radiosity.mesh_json(p, w); }, json_type);
  text_endpoint(
      "/api/radiosity/start", [&](P p, W w) { return radiosity.start_json(p, w); }, json_type);
  text_endpoint(
      "/api/radiosity/step", [&](P p, W) { return radiosity.step_json(p); }, json_type);
  text_endpoint(
      "/api/hemicube", [&](P p, W w) { return radiosity.hemicube_json(p, w); }, json_type);
  text_endpoint(
      "/api/hemicube/study", [&](P p, W w) { return radiosity.hemicube_study_json(p, w); }, json_type);
  text_endpoint(
      "/api/hierarchy", [&](P p, W w) { return hierarchy.hierarchy_json(p, w); }, json_type);
  text_endpoint(
      "/api/compare",
      [&](P p, W) {
        const Query q(p, {});
        return compare.list_json();
      },
      json_type);
  text_endpoint(
      "/api/compare/image", [&](P p, W) { return compare.image_png(p); }, "image/png");
  text_endpoint(
      "/api/compare/stats", [&](P p, W) { return compare.stats_json(p); }, json_type);
  // The reference lab's answers to the same requests (lab_reference.hpp): only these endpoints.
  server.Get(R"(/api/reference/(info|scene|render|trace|radiosity/mesh|radiosity/start|radiosity/step))",
             [&](const httplib::Request& request, httplib::Response& response) {
               guarded(response, [&] {
                 const std::string tab = tab_of(request);
                 if (!reference.available())
                   throw NotFound("no reference to compare with: " + reference.why());
                 const std::size_t query = request.target.find('?');
                 const ReferenceLab::Answer a =
                     reference.get("/api/" + request.matches[1].str() +
                                       (query == std::string::npos ? "" : request.target.substr(query)),
                                   tab);
                 response.status = a.status;
                 response.set_content(a.body, a.type.empty() ? json_type : a.type);
               });
             });

  signals.start(server, [&] { reference.terminate(); });
  std::cout << "illum lab: http://" << host << "/ (scene " << trace.default_scene()
            << "; the ray tree, radiosity shot by shot, the hemicube, the hierarchy and your pictures; "
               "Ctrl-C stops it)"
            << std::endl;
  const bool listened = server.listen_after_bind();
  if (signals.signal() != 0) {
    std::cerr << "illum lab: stopped\n";
    return 0;
  }
  if (!listened) throw std::runtime_error("the server stopped listening on " + host);
  return 0;
}

}  // namespace illum::lab
