#include "lab/lab_radiosity.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <numbers>
#include <optional>
#include <random>
#include <thread>

#include <nlohmann/json.hpp>

#include "illum/core/error.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/radiosity/form_factor_analytic.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "illum/radiosity/patch_occluders.hpp"
#include "illum/radiosity/radiosity_solvers.hpp"
#include "illum/radiosity/radiosity_system.hpp"
#include "illum/radiosity/vertex_colours.hpp"

namespace illum::lab {

// Outside the unnamed namespace: RadiosityLab::Session, a type with linkage, holds one.
enum class Method { progressive, jacobi, gauss_seidel, southwell };

namespace {

using nlohmann::json;

// Colours and factors go to the browser as floats: 7 digits are plenty to
// paint with, and a 2,124-patch step stays small.
json floats(const double* v, std::size_t n) {
  json out = json::array();
  for (std::size_t i = 0; i < n; ++i) out.push_back(to_float(v[i]));
  return out;
}

std::string base64(const void* data, std::size_t bytes) {
  static const char table[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* p = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((bytes + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes; i += 3) {
    const unsigned v = p[i] << 16 | (i + 1 < bytes ? p[i + 1] << 8 : 0) | (i + 2 < bytes ? p[i + 2] : 0);
    out += table[v >> 18 & 63];
    out += table[v >> 12 & 63];
    out += i + 1 < bytes ? table[v >> 6 & 63] : '=';
    out += i + 2 < bytes ? table[v & 63] : '=';
  }
  return out;
}

// Little-endian float32 of each value, base64: a typed array for the browser
// (a 2,124-patch step is a third of its size as JSON numbers, and parses at once).
std::string float32_base64(const std::vector<double>& v) {
  std::vector<float> f(v.size());
  std::transform(v.begin(), v.end(), f.begin(), to_float);
  return base64(f.data(), f.size() * sizeof(float));
}

std::string float32_base64(const std::vector<Color>& v) {
  std::vector<double> flat;
  flat.reserve(3 * v.size());
  for (const Color& c : v) flat.insert(flat.end(), {c.r, c.g, c.b});
  return float32_base64(flat);
}

template <class T>
std::shared_ptr<T> find_cached(std::vector<std::pair<std::string, std::shared_ptr<T>>>& cache,
                               const std::string& key) {
  for (auto it = cache.begin(); it != cache.end(); ++it)
    if (it->first == key) {
      auto found = it->second;
      std::rotate(cache.begin(), it, it + 1);
      return found;
    }
  return nullptr;
}

template <class T>
void keep(std::vector<std::pair<std::string, std::shared_ptr<T>>>& cache, const std::string& key,
          std::shared_ptr<T> value, std::size_t most) {
  cache.insert(cache.begin(), {key, std::move(value)});
  if (cache.size() > most) cache.pop_back();
}

const std::vector<std::string> method_names = {"progressive", "jacobi", "gauss_seidel", "southwell"};

std::string random_id() {
  static std::mutex m;
  static std::mt19937_64 rng(std::random_device{}());
  const std::lock_guard lock(m);
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(rng()));
  return buf;
}

constexpr std::size_t max_patches = 20000;  // the most a request may ask for
// The most a mesh may have: the edge shrinks by 3% a step, so a mesh of at least 20,000 patches
// can overshoot by a step's 6% (the Cornell box: 20,000 asked, 21,248 meshed).
constexpr std::size_t max_mesh_patches = 22000;
constexpr std::size_t max_matrix_patches = 3000;  // 72 MB of form factors
constexpr int max_matrix_resolution = 256;        // a whole matrix of rows at most this fine
constexpr std::size_t max_matrix_sessions = 4;    // sessions holding a whole matrix (the oldest go first)
// A step stops after this much work, with what it has done: a request for 20,000 shots of a
// 20,000-patch mesh must not hold the session for an hour (Ctrl-C and a newer step stop it at once).
constexpr double step_seconds = 15;
// A target within this angle of the receiver's plane is seen edge-on (hemicube_json).
constexpr double edge_on_degrees = 1.0;
constexpr std::size_t max_sessions = 16, max_meshes = 4, max_matrices = 2, max_visibility = 8;

}  // namespace

struct RadiosityLab::Mesh {
  std::string key, scene_id;
  double edge = 0;
  RadiosityScene scene;
  SharedVertexMesh shared;
  double emitted = 0;  // total_power of the emissions
  std::string json;
  // Lesson 08's BVH over the patches, for the hemicube view's visibility (built on first use).
  mutable std::once_flag occluders_built;
  mutable std::unique_ptr<PatchOccluders> occluders;
};

struct RadiosityLab::Session {
  std::mutex mutex;  // one step at a time per session
  std::string id;
  std::shared_ptr<const Mesh> mesh;
  Method method = Method::progressive;
  int resolution = 128;
  double omega = 1.0;
  // Progressive: rows drawn per shot, on one thread: a row of the 2,124-patch box takes half a
  // millisecond, and form_factor_row_parallel's OpenMP threads, spinning at their barrier on a
  // shared 2-core machine, made it 40 ms.
  std::unique_ptr<Hemicube> hemicube;
  HemicubeBuffers buffers;
  std::shared_ptr<const FormFactorMatrix> f;  // the sweeps and Southwell
  ProgressiveState state;
  std::vector<Color> b, next, residual;
  std::vector<double> row;
  std::vector<Color> update;  // progressive: what the last shot added to each radiosity
  std::size_t steps = 0;
  int shooter = -1;
};

std::shared_ptr<const RadiosityLab::Mesh> RadiosityLab::mesh(const Query& q, const Work& work) {
  const SceneEntry& entry = find_scene(scenes_, q.name_or("scene", "cornell"));
  if (q.has("patches") && q.has("edge")) throw BadRequest("give 'patches' or 'edge', not both");
  const bool by_edge = q.has("edge");
  const double edge_asked = by_edge ? q.number("edge", 1e-6, 1e9) : 0;
  const std::size_t wanted = static_cast<std::size_t>(q.integer_or("patches", 1, max_patches, 2000));
  const std::string key =
      entry.id + (by_edge ? "|edge " + std::to_string(edge_asked) : "|at least " + std::to_string(wanted));
  {
    const std::lock_guard lock(mutex_);
    if (auto m = find_cached(meshes_, key)) return m;
  }
  auto m = std::make_shared<Mesh>();
  m->key = key, m->scene_id = entry.id;
  const auto load = [&](double edge) {
    // Counted before meshing: the loader refuses beyond max_scene_patches, the lab beyond max_mesh_patches.
    work.check();
    RadiosityScene s = load_radiosity_scene(entry.source, 1e300);
    double count = 0;
    for (const RadiositySurface& surface : s.surfaces)
      count += radiosity_patch_grid(surface.polygon, edge).patches;
    if (count > static_cast<double>(max_mesh_patches)) return std::optional<RadiosityScene>();
    return std::optional<RadiosityScene>(load_radiosity_scene(entry.source, edge));
  };
  if (by_edge) {
    auto s = load(edge_asked);
    if (!s)
      throw BadRequest(q.asked("edge") + " would mesh scene '" + entry.id + "' into more than " +
                       std::to_string(max_mesh_patches) + " patches");
    m->scene = std::move(*s), m->edge = edge_asked;
  } else {
    // Lesson 11's figure: edge 240·0.97^k for the least k giving at least `wanted` patches
    // (the count only grows with k, so bisection finds the k its loop stops at), the edge
    // computed by the same repeated products as that loop.
    const auto edge_at = [](int k) {
      double edge = 240.0;
      for (int j = 0; j < k; ++j) edge *= 0.97;
      return edge;
    };
    const auto count_at = [&](int k) {
      const auto s = load(edge_at(k));
      return s ? s->patches.size() : max_mesh_patches + 1;
    };
    int lo = 0, hi = 1000;
    if (count_at(hi) < wanted)
      throw BadRequest("scene '" + entry.id + "' cannot be meshed into " + std::to_string(wanted) +
                       " patches");
    while (lo < hi) {
      const int mid = (lo + hi) / 2;
      if (count_at(mid) >= wanted)
        hi = mid;
      else
        lo = mid + 1;
    }
    const double edge = edge_at(lo);
    auto s = load(edge);
    if (!s || s->patches.size() > max_mesh_patches)
      throw BadRequest("scene '" + entry.id + "' meshed into at least " + std::to_string(wanted) +
                       " patches has more than " + std::to_string(max_mesh_patches));
    m->scene = std::move(*s), m->edge = edge;
  }
  const std::vector<Patch>& patches = m->scene.patches;
  m->emitted = total_power(patches, emissions(patches));
  if (!(m->emitted > 0))
    throw BadRequest("no surface of scene '" + entry.id + "' emits light: nothing to solve");
  m->shared = share_vertices(patches);
  json surfaces = json::array();
  for (const RadiositySurface& s : m->scene.surfaces)
    surfaces.push_back(
        {{"name", s.name}, {"material", s.material}, {"first", s.first_patch}, {"count", s.patch_count}});
  json vertices = json::array(), counts = json::array(), reflectance = json::array(),
       emission = json::array(), area = json::array(), centroid = json::array(), normal = json::array();
  for (const Patch& p : patches) {
    counts.push_back(p.vertices.size());
    for (const Point3& v : p.vertices)
      for (int k = 0; k < 3; ++k) vertices.push_back(v[k]);
    for (int k = 0; k < 3; ++k) {
      reflectance.push_back(p.reflectance[k]), emission.push_back(p.emission[k]);
      centroid.push_back(p.centroid[k]), normal.push_back(p.normal[k]);
    }
    area.push_back(p.area);
  }
  json camera = nullptr;
  if (m->scene.camera)
    camera = {{"eye", triple(m->scene.camera->eye)},
              {"target", triple(m->scene.camera->target)},
              {"up", triple(m->scene.camera->up)},
              {"vertical_fov_degrees", m->scene.camera->vertical_fov_degrees}};
  m->json = json{{"scene", entry.id},
                 {"name", m->scene.name},
                 {"edge", m->edge},
                 {"patches", patches.size()},
                 {"emitted_power", m->emitted},
                 {"camera", camera},
                 {"surfaces", surfaces},
                 {"vertex_counts", counts},
                 {"vertices", vertices},
                 {"reflectance", reflectance},
                 {"emission", emission},
                 {"area", area},
                 {"centroid", centroid},
                 {"normal", normal}}
                .dump() +
            "\n";
  const std::lock_guard lock(mutex_);
  if (auto existing = find_cached(meshes_, key)) return existing;
  keep(meshes_, key, std::shared_ptr<const Mesh>(m), max_meshes);
  return m;
}

std::shared_ptr<const FormFactorMatrix> RadiosityLab::matrix(const std::shared_ptr<const Mesh>& m,
                                                             int resolution, const Work& work) {
  const std::string key = m->key + "|" + std::to_string(resolution);
  const std::lock_guard one_at_a_time(matrix_mutex_);
  {
    const std::lock_guard lock(mutex_);
    if (auto f = find_cached(matrices_, key)) return f;
  }
  const std::vector<Patch>& patches = m->scene.patches;
  if (patches.size() > max_matrix_patches)
    throw BadRequest("the sweeps and Southwell need the whole " + std::to_string(patches.size()) + " × " +
                     std::to_string(patches.size()) + " matrix; the lab draws it for at most " +
                     std::to_string(max_matrix_patches) + " patches (ask for fewer, or use progressive)");
  const Hemicube hemicube(resolution);
  auto f = std::make_shared<FormFactorMatrix>(patches.size());
  parallel_for(
      patches.size(), [] { return HemicubeBuffers(); },
      [&](HemicubeBuffers& buffers, std::size_t i) {
        work.check();
        hemicube.form_factor_row(patches, i, f->row(i), buffers);
      });
  const std::lock_guard lock(mutex_);
  keep(matrices_, key, std::shared_ptr<const FormFactorMatrix>(f), max_matrices);
  return f;
}

std::string RadiosityLab::mesh_json(const Params& params, const Work& work) {
  const Query q(params, {"scene", "patches", "edge"});
  return mesh(q, work)->json;
}

std::shared_ptr<RadiosityLab::Session> RadiosityLab::session(const std::string& id) {
  const std::lock_guard lock(mutex_);
  if (auto s = find_cached(sessions_, id)) return s;
  throw NotFound("no session '" + id + "' (the lab keeps the " + std::to_string(max_sessions) +
                 " most recent; start another)");
}

namespace {

double unshot_fraction(const std::vector<Patch>& patches, const std::vector<Color>& residual,
                       double emitted) {
  double p = 0;  // total_power of |r|: a residual can be negative in a channel
  for (std::size_t i = 0; i < patches.size(); ++i)
    p += patches[i].area * (std::abs(residual[i].r) + std::abs(residual[i].g) + std::abs(residual[i].b));
  return p / emitted;
}

}  // namespace

std::string RadiosityLab::start_json(const Params& params, const Work& work) {
  const Query q(params, {"scene", "patches", "edge", "method", "resolution", "omega"});
  const auto m = mesh(q, work);
  auto s = std::make_shared<Session>();
  s->id = random_id();
  s->mesh = m;
  const std::string method = q.choice_or("method", method_names, "progressive");
  s->method =
      static_cast<Method>(std::find(method_names.begin(), method_names.end(), method) - method_names.begin());
  const long long resolution = q.integer_or("resolution", 2, 1024, 128);
  if (resolution % 2)
    throw BadRequest("parameter 'resolution' = " + std::to_string(resolution) +
                     " is odd: the hemicube's side faces are half as tall");
  s->resolution = static_cast<int>(resolution);
  s->omega = q.number_or("omega", 0.05, 1.95, 1.0);
  if (q.has("omega") && s->method != Method::gauss_seidel)
    throw BadRequest("parameter 'omega' (over-relaxation) is for method gauss_seidel only");
  const std::vector<Patch>& patches = m->scene.patches;
  const std::size_t n = patches.size();
  if (s->method == Method::progressive) {
    s->state = progressive_start(patches);  // the student's Task 6a
    s->hemicube = std::make_unique<Hemicube>(s->resolution);
    s->row.assign(n, 0.0);
  } else {
    if (s->resolution > max_matrix_resolution)
      throw BadRequest("parameter 'resolution' = " + std::to_string(s->resolution) +
                       ": the sweeps and Southwell draw the whole matrix, every row at most " +
                       std::to_string(max_matrix_resolution) + " pixels across");
    // Named as the request asked (patches=5000), not as the mesh it made: the mesh has at least
    // that many patches, often a few more.
    if (n > max_matrix_patches)
      throw BadRequest(
          (q.has("edge")      ? q.asked("edge")
           : q.has("patches") ? q.asked("patches")
                              : std::string("the default mesh")) +
          " meshes scene '" + m->scene_id + "' into " + std::to_string(n) + " patches; method '" + method +
          "' needs the whole form-factor matrix, which the lab draws for at most " +
          std::to_string(max_matrix_patches) + " patches: ask for fewer, or use method 'progressive'");
    s->f = matrix(m, s->resolution, work);
    check_radiosity_system(patches, *s->f);
    s->b.assign(n, Color(0.0));
    s->residual = emissions(patches);
  }
  {
    const std::lock_guard lock(mutex_);
    if (s->f) {  // at most a few sessions keep a whole matrix alive: the oldest of them go first
      std::size_t holding = 0;
      for (auto it = sessions_.begin(); it != sessions_.end();)
        if (it->second->f && ++holding >= max_matrix_sessions)
          it = sessions_.erase(it);
        else
          ++it;
    }
    keep(sessions_, s->id, s, max_sessions);
  }
  return json{{"session", s->id},  {"method", method},     {"resolution", s->resolution},
              {"omega", s->omega}, {"scene", m->scene_id}, {"patches", n},
              {"edge", m->edge},   {"fraction", 1.0}}
             .dump() +
         "\n";
}

std::string RadiosityLab::step_json(const Params& params) {
  const Query q(params, {"session", "steps", "row", "vertex", "rule", "update"});
  const std::string id = q.name("session", 32);
  const auto s = session(id);
  // Registered before waiting for the session: a newer step stops the one running now.
  const Work work("step|" + id);
  const std::lock_guard lock(s->mutex);
  const Mesh& m = *s->mesh;
  const std::vector<Patch>& patches = m.scene.patches;
  const std::size_t n = patches.size();
  const bool sweeps = s->method == Method::jacobi || s->method == Method::gauss_seidel;
  const long long steps = q.integer_or("steps", 0, sweeps ? 500 : 20000, 1);
  const bool want_row = q.flag_or("row", false), vertex = q.flag_or("vertex", false);
  const bool want_update = q.flag_or("update", false);
  const std::string rule = q.choice_or("rule", {"average", "extrapolate"}, "extrapolate");
  json points = json::array(), shooters = json::array();
  Stopwatch watch;
  double row_seconds = 0;
  bool done = false;
  if (steps > 0) s->shooter = -1, s->update.clear();  // steps=0 asks again about the last step
  bool truncated = false;
  for (long long k = 0; k < steps; ++k) {
    if (k > 0) {
      work.check();  // the first step always runs: a step of 1 is never lost
      if (watch.seconds() > step_seconds) {
        truncated = true;
        break;
      }
    }
    double fraction = 0;
    if (s->method == Method::progressive) {
      if (!(total_power(patches, s->state.unshot) > 0)) {
        done = true;
        break;
      }
      const std::size_t i = choose_shooter(patches, s->state.unshot);  // Task 6b
      Stopwatch row_watch;
      s->hemicube->form_factor_row(patches, i, s->row, s->buffers);  // lesson 10's deltas
      row_seconds += row_watch.seconds();
      if (want_update && k + 1 == steps) s->update = s->state.radiosity;
      shoot(patches, i, s->row, s->state);  // Task 6c
      if (want_update && k + 1 == steps)
        for (std::size_t j = 0; j < n; ++j) s->update[j] = s->state.radiosity[j] - s->update[j];
      s->shooter = static_cast<int>(i);
      fraction = total_power(patches, s->state.unshot) / m.emitted;
    } else if (s->method == Method::southwell) {
      const std::size_t i = southwell_step(patches, *s->f, s->b, s->residual);  // Task 5
      s->shooter = static_cast<int>(i);
      fraction = unshot_fraction(patches, s->residual, m.emitted);
    } else {
      if (s->method == Method::jacobi) {
        jacobi_sweep(patches, *s->f, s->b, s->next);  // Task 3
        std::swap(s->b, s->next);
      } else {
        gauss_seidel_sweep(patches, *s->f, s->b, s->omega);  // Task 4
      }
      s->residual = radiosity_residual(patches, *s->f, s->b);
      fraction = unshot_fraction(patches, s->residual, m.emitted);
    }
    ++s->steps;
    points.push_back(json::array({s->steps, fraction}));
    shooters.push_back(s->shooter);
  }
  const double seconds = watch.seconds();
  const std::vector<Color>& b = s->method == Method::progressive ? s->state.radiosity : s->b;
  json out{{"session", s->id},       {"steps", s->steps},  {"done", done},
           {"truncated", truncated}, {"points", points},   {"shooters", shooters},
           {"shooter", s->shooter},  {"seconds", seconds}, {"row_seconds", row_seconds}};
  out["fraction"] = s->method == Method::progressive ? total_power(patches, s->state.unshot) / m.emitted
                                                     : unshot_fraction(patches, s->residual, m.emitted);
  out["radiosity"] = float32_base64(b);
  // What the shooter sent: progressive, its row F_i· (drawn by this shot's
  // hemicube); Southwell, the column F_·i that carried its residual.
  out["row"] = nullptr;
  if (want_row && s->shooter >= 0 && s->method == Method::progressive) {
    out["row"] = float32_base64(s->row);
    out["row_kind"] = "row";
  } else if (want_row && s->shooter >= 0) {
    std::vector<double> column(n);
    for (std::size_t j = 0; j < n; ++j) column[j] = (*s->f)(j, static_cast<std::size_t>(s->shooter));
    out["row"] = float32_base64(column);
    out["row_kind"] = "column";
  }
  // What the last shot added to every radiosity (progressive): the page holds it against the reference's.
  out["update"] = nullptr;
  if (want_update && s->method == Method::progressive && s->shooter >= 0 && s->update.size() == n)
    out["update"] = float32_base64(s->update);
  out["ambient"] = nullptr;
  if (s->method == Method::progressive) {
    try {
      out["ambient"] = triple(ambient_term(patches, s->state.unshot));  // Task 7
    } catch (const NotImplemented& e) {
      out["ambient_error"] = e.message();
    }
  }
  if (vertex) {
    try {
      const auto corners =
          corner_radiosity(m.shared, b,  // lesson 12's exercise
                           rule == "average" ? VertexColourRule::average : VertexColourRule::extrapolate);
      std::vector<Color> flat;
      for (const auto& c : corners) flat.insert(flat.end(), c.begin(), c.end());
      out["vertex"] = float32_base64(flat);
    } catch (const NotImplemented& e) {
      out["vertex_error"] = e.message();
    }
  }
  return out.dump() + "\n";
}

std::shared_ptr<const std::vector<char>> RadiosityLab::seen_whole(const Mesh& m, std::size_t patch,
                                                                  const Work& work) {
  const std::string key = m.key + "|" + std::to_string(patch);
  {
    const std::lock_guard lock(mutex_);
    if (auto v = find_cached(visibility_, key)) return v;  // shared: another request may evict it meanwhile
  }
  // Seen whole: the segments from the centroid to the target's centroid and to
  // its corners pulled 2% towards its centroid (off the edges it shares) cross
  // no patch; asked of lesson 08's BVH over the patches (PatchOccluders: brute
  // force, lesson 09's mutually_visible, took minutes at 20,000 patches).
  const std::vector<Patch>& patches = m.scene.patches;
  std::call_once(m.occluders_built, [&] { m.occluders = std::make_unique<PatchOccluders>(patches); });
  const PatchOccluders& occluders = *m.occluders;
  const Patch& from = patches[patch];
  auto seen = std::make_shared<std::vector<char>>(patches.size(), 0);
  parallel_for(
      patches.size(), [] { return 0; },
      [&](int&, std::size_t j) {
        if (j % 256 == 0) work.check();
        const Patch& to = patches[j];
        if (j == patch || point_polygon_form_factor(from.centroid, from.normal, to) <= 0) return;
        bool all = occluders.mutually_visible(from.centroid, to.centroid);
        for (std::size_t k = 0; all && k < to.vertices.size(); ++k)
          all =
              occluders.mutually_visible(from.centroid, to.centroid + 0.98 * (to.vertices[k] - to.centroid));
        (*seen)[j] = all ? 1 : 0;
      });
  const std::lock_guard lock(mutex_);
  keep(visibility_, key, std::shared_ptr<const std::vector<char>>(seen), max_visibility);
  return seen;
}

namespace {

// The row against the exact factors from the centroid, over the targets seen whole. The mean
// relative error counts every target alike, so it is led by the targets seen edge-on: within
// edge_on_degrees of the receiver's plane (as the two triangles of the Cornell box's red wall, whose
// corners lie 3.2 mm out of one plane, are from each other), they fall in the side faces' lowest
// pixel rows at every resolution, where a pixel's delta form factor (taken at its centre) is far
// from their tiny factors: their relative errors stay near 1. So the errors are also given without them
// (mean_rel_above) and weighted by the exact factor (weighted_rel = Σ|ΔF| / ΣF, the share of the row's energy
// put on the wrong target).
struct RowErrors {
  double max_abs = 0, mean_abs = 0, mean_rel = 0, mean_rel_above = 0, weighted_rel = 0, edge_on_factor = 0;
  std::size_t targets = 0, edge_on = 0;
};

// Whether every corner of `to` lies within edge_on_degrees of the plane of `from`.
bool edge_on(const Patch& from, const Patch& to) {
  const double most = std::sin(edge_on_degrees * std::numbers::pi / 180.0);
  for (const Point3& v : to.vertices) {
    const Vec3 d = v - from.centroid;
    if (dot(from.normal, d) > most * length(d)) return false;
  }
  return true;
}

RowErrors row_errors(const std::vector<Patch>& patches, std::size_t i, const std::vector<double>& row,
                     const std::vector<double>& exact, const std::vector<char>& seen) {
  RowErrors e;
  double exact_sum = 0;
  std::size_t above = 0;
  for (std::size_t j = 0; j < row.size(); ++j) {
    if (!seen[j] || !(exact[j] > 0)) continue;
    const double d = std::abs(row[j] - exact[j]);
    e.max_abs = std::max(e.max_abs, d), e.mean_abs += d, e.mean_rel += d / exact[j];
    e.weighted_rel += d, exact_sum += exact[j];
    if (edge_on(patches[i], patches[j]))
      ++e.edge_on, e.edge_on_factor += exact[j];
    else
      ++above, e.mean_rel_above += d / exact[j];
    ++e.targets;
  }
  if (e.targets) e.mean_abs /= static_cast<double>(e.targets), e.mean_rel /= static_cast<double>(e.targets);
  if (above) e.mean_rel_above /= static_cast<double>(above);
  if (exact_sum > 0) e.weighted_rel /= exact_sum;
  return e;
}

json errors_json(const RowErrors& e) {
  return {{"targets", e.targets},
          {"max_abs", e.max_abs},
          {"mean_abs", e.mean_abs},
          {"mean_rel", e.mean_rel},
          {"mean_rel_above", e.mean_rel_above},
          {"weighted_rel", e.weighted_rel},
          {"edge_on", e.edge_on},
          {"edge_on_factor", e.edge_on_factor},
          {"edge_on_degrees", edge_on_degrees}};
}

// Lambert's contour formula from the centroid of patch i to every other patch (lesson 09, Task 2).
std::vector<double> exact_row(const std::vector<Patch>& patches, std::size_t i) {
  std::vector<double> exact(patches.size(), 0.0);
  for (std::size_t j = 0; j < patches.size(); ++j)
    if (j != i) exact[j] = point_polygon_form_factor(patches[i].centroid, patches[i].normal, patches[j]);
  return exact;
}

}  // namespace

std::string RadiosityLab::hemicube_json(const Params& params, const Work& work) {
  const Query q(params, {"scene", "patches", "edge", "patch", "resolution"});
  const auto m = mesh(q, work);
  const std::vector<Patch>& patches = m->scene.patches;
  const auto i = static_cast<std::size_t>(q.integer("patch", 0, static_cast<long long>(patches.size()) - 1));
  const long long res = q.integer_or("resolution", 2, 512, 64);
  if (res % 2)
    throw BadRequest("parameter 'resolution' = " + std::to_string(res) +
                     " is odd: the hemicube's side faces are half as tall");
  const Hemicube hemicube(static_cast<int>(res));  // lesson 10's deltas
  HemicubeBuffers buffers;
  std::vector<double> row(patches.size(), 0.0);
  Stopwatch watch;
  hemicube.form_factor_row(patches, i, row, buffers);
  const double seconds = watch.seconds();
  json faces = json::array();
  const char* names[] = {"top", "+x", "-x", "+y", "-y"};
  for (int f = 0; f < 5; ++f) {
    const auto face = static_cast<HemicubeFace>(f);
    const int w = HemicubeBuffers::face_width(static_cast<int>(res)),
              h = HemicubeBuffers::face_height(static_cast<int>(res), face);
    faces.push_back(
        {{"name", names[f]},
         {"width", w},
         {"height", h},
         {"items", base64(buffers.face_items(face).data(), buffers.face_items(face).size_bytes())}});
  }
  double sum = 0;
  for (const double v : row) sum += v;
  const Patch& p = patches[i];
  std::string surface;
  for (const RadiositySurface& s : m->scene.surfaces)
    if (i >= s.first_patch && i < s.first_patch + s.patch_count) surface = s.name;
  json out{
      {"patch", i},
      {"surface", surface},
      {"centroid", triple(p.centroid)},
      {"normal", triple(p.normal)},
      {"area", p.area},
      {"resolution", res},
      {"faces", faces},
      {"deltas",
       {{"top", float32_base64(hemicube.deltas().top)}, {"side", float32_base64(hemicube.deltas().side)}}},
      {"row", floats(row.data(), row.size())},
      {"sum", sum},
      {"seconds", seconds}};
  out["exact"] = nullptr;
  try {
    const std::vector<double> exact = exact_row(patches, i);
    const auto seen_list_kept = seen_whole(*m, i, work);
    const std::vector<char>& seen = *seen_list_kept;
    out["exact"] = floats(exact.data(), exact.size());
    json seen_list = json::array();
    for (const char c : seen) seen_list.push_back(c != 0);
    out["seen_whole"] = seen_list;
    out["errors"] = errors_json(row_errors(patches, i, row, exact, seen));
  } catch (const NotImplemented& e) {
    out["exact_error"] = e.message();
  }
  return out.dump() + "\n";
}

std::string RadiosityLab::hemicube_study_json(const Params& params, const Work& work) {
  const Query q(params, {"scene", "patches", "edge", "patch"});
  const auto m = mesh(q, work);
  const std::vector<Patch>& patches = m->scene.patches;
  const auto i = static_cast<std::size_t>(q.integer("patch", 0, static_cast<long long>(patches.size()) - 1));
  const std::vector<double> exact = exact_row(patches, i);
  const auto seen_kept = seen_whole(*m, i, work);
  const std::vector<char>& seen = *seen_kept;
  json rows = json::array();
  for (const int res : {8, 16, 32, 64, 128, 256, 512}) {
    work.check();
    const Hemicube hemicube(res);
    HemicubeBuffers buffers;
    std::vector<double> row(patches.size(), 0.0);
    Stopwatch watch;
    hemicube.form_factor_row(patches, i, row, buffers);
    const double seconds = watch.seconds();
    double sum = 0;
    for (const double v : row) sum += v;
    json r = errors_json(row_errors(patches, i, row, exact, seen));
    r["resolution"] = res, r["sum"] = sum, r["seconds"] = seconds;
    rows.push_back(r);
  }
  return json{{"patch", i}, {"rows", rows}}.dump() + "\n";
}

}  // namespace illum::lab
