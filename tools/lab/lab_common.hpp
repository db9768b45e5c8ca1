#pragma once
// What every part of `illum lab` shares (docs/lab.md): the errors a request
// can end with, the strict reading of query parameters, and the render
// settings `illum render`, `illum trace` and the lab have in common.
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "illum/core/error.hpp"
#include "illum/core/image.hpp"
#include "illum/core/vec.hpp"
#include "illum/trace/ray_tree_render.hpp"

namespace illum::lab {

// A request the lab refuses: answered 400 with this message.
struct BadRequest : std::runtime_error {
  using std::runtime_error::runtime_error;
};
// Something the request names that does not exist (a session that expired): 404.
struct NotFound : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A request stopped before its end (answered 409, or 503 when the lab is stopping).
struct Cancelled : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using Params = std::multimap<std::string, std::string>;

// One request's long work. Its loops call check() between rows, shots and
// patches (each a few hundredths of a second), so that it stops within half a
// second of Ctrl-C (stop_all_work) or of a newer Work with the same key: the
// page's next render replaces its last one, a session's next step the one
// still running. An empty key is stopped by Ctrl-C only.
class Work {
 public:
  explicit Work(std::string key = "");
  ~Work();
  Work(const Work&) = delete;
  Work& operator=(const Work&) = delete;
  void check() const;  // throws Cancelled

 private:
  std::string key_;
  std::shared_ptr<std::atomic<std::uint64_t>> newest_;
  std::uint64_t mine_ = 0;
};
void stop_all_work();
bool lab_stopping();

// The query parameters of one request, read strictly: a parameter the
// endpoint does not know, one given twice, an empty value, a number that
// does not parse completely or lies outside its range is a BadRequest whose
// message names the parameter, the value and what was expected.
class Query {
 public:
  Query(const Params& params, std::vector<std::string> known);

  bool has(const std::string& name) const;
  // An integer in [lo, hi], written as decimal digits with an optional '-'.
  long long integer(const std::string& name, long long lo, long long hi) const;
  long long integer_or(const std::string& name, long long lo, long long hi, long long fallback) const;
  // A finite number in [lo, hi].
  double number(const std::string& name, double lo, double hi) const;
  double number_or(const std::string& name, double lo, double hi, double fallback) const;
  // One of `allowed`.
  std::string choice(const std::string& name, const std::vector<std::string>& allowed) const;
  std::string choice_or(const std::string& name, const std::vector<std::string>& allowed,
                        const std::string& fallback) const;
  // 0/1 or false/true.
  bool flag_or(const std::string& name, bool fallback) const;
  // Letters, digits and " _-.,()" only, at most max_length bytes (names of scenes, lessons, files).
  std::string name(const std::string& name, std::size_t max_length = 80) const;
  std::string name_or(const std::string& name, const std::string& fallback,
                      std::size_t max_length = 80) const;
  // "patches=5000": a parameter as the request wrote it, for a message that names what was asked.
  // For a value already read by integer(), number() or name() (and so known to be plain text).
  std::string asked(const std::string& name) const;

 private:
  const std::string& value(const std::string& name) const;
  std::map<std::string, std::string> values_;
};

// The parameters of the request for `target` ("/api/render?scene=x&width=64") as the server decoded
// them (`decoded`), once the raw query is checked for what decoding hides: a parameter without a
// name ("?=1", "?a=1&=2"), which the decoder would read as a parameter named by its value, is a
// BadRequest naming its place.
Params checked_params(const std::string& target, Params decoded);

// The scenes a request may name: the command line's (a shipped name, or a
// file named by its stem), then every shipped scene. `source` is what
// load_scene and load_radiosity_scene take.
struct SceneEntry {
  std::string id, source;
};
std::vector<SceneEntry> scene_catalogue(const std::string& command_line_scene);
// The entry called `id`; BadRequest naming the known ones when there is none.
const SceneEntry& find_scene(const std::vector<SceneEntry>& catalogue, const std::string& id);

// A double as a float for the browser: beyond the float range it becomes an
// infinity (a plain cast would be undefined behaviour there).
float to_float(double value);

// A point or vector as the browser reads it: [x, y, z].
nlohmann::json triple(const Vec3& v);

// {"error": message} as text.
std::string error_json(const std::string& message);

// The sky colour every ray that misses gets in `illum render`, `illum trace` and the lab.
Color cli_background();

// A PNG of a linear image (sRGB, 8 bits), in memory.
std::string png_bytes(const Image& image);

// Runs body(state, i) for i in [0, n) on every core, each thread with its own
// state from make(); the first exception (a NotImplemented, a Cancelled)
// stops the others and is rethrown here once every thread has stopped.
template <class Make, class Body>
void parallel_for(std::size_t n, Make make, Body body) {
  const std::size_t threads = std::max(1u, std::min(8u, std::thread::hardware_concurrency()));
  std::atomic<std::size_t> next{0};
  std::mutex error_mutex;
  std::exception_ptr error;
  const auto work = [&] {
    try {
      auto state = make();
      for (std::size_t i; (i = next.fetch_add(1)) < n;) body(state, i);
    } catch (...) {
      const std::lock_guard lock(error_mutex);
      if (!error) error = std::current_exception();
      next = n;
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < std::min(threads, n); ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace illum::lab
