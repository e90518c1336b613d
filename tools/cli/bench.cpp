// curvenet bench [INPUT] [--resolution R] [--points P] [--threads T] [--json]
//
// The G¹-vs-G² cost comparison in the form of [SV14] Table 1, measured in
// one run: per scheme the ribbon/fence construction time, the pointwise
// evaluation of P random domain points, the evaluation of every face
// interior's samples at resolution R through evaluation plans
// (evaluateFaceInteriors: positions, into one reused buffer) — cold (a
// freshly built surface with the plan cache emptied: plans and ribbon tables
// built), warm (plans and tables ready), on one thread and on all threads —
// and the whole tessellation (positions, normals from exact derivatives,
// triangles; into one reused Mesh, and as a fresh Mesh each run); then batches at 65 536 random domain points through
// Surface::evaluatePositions and, with du, dv and normals, Surface::evaluate.
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>

#include <time.h>

#include "commands.hpp"
#include "progress.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/io.hpp"
#include "curvenet/kernels/kernels.hpp"
#include "curvenet/tessellate.hpp"
#include "report.hpp"

namespace curvenet::cli {

namespace {

using Clock = std::chrono::steady_clock;

/// The calling thread's CPU time, s.
double threadSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Fastest of repeated runs of f (at least `repeats`, and until ~0.3 s
/// spent), wall clock; with `cpu`, also the fastest run's share of the
/// calling thread's CPU time (one-thread runs: the work's own rate, which
/// other jobs on a shared machine disturb far less than the wall clock).
template <class F> double fastest(F &&f, int repeats = 3, double *cpu = nullptr) {
  double best = INFINITY, spent = 0, bestCpu = INFINITY;
  for (int k = 0; k < repeats || (spent < 0.3 && k < 50); ++k) {
    const auto t0 = Clock::now();
    const double c0 = threadSeconds();
    f();
    const double c = threadSeconds() - c0;
    const double s = std::chrono::duration<double>(Clock::now() - t0).count();
    best = std::min(best, s), spent += s, bestCpu = std::min(bestCpu, c);
  }
  if (cpu) *cpu = bestCpu;
  return best;
}

struct SchemeFigures {
  Scheme scheme{};
  std::string name;
  double build = 0;          ///< fences and ribbons (Surface::build), s
  double pointwise = 0;      ///< `points` random domain points through Surface::evaluate, s
  std::size_t interiorPoints = 0;
  double cold = 0, warm = 0; ///< face-interior evaluation on one thread, cold / warm, s
  double warmThreads = 0;    ///< warm on all threads, s
  std::size_t meshPoints = 0;
  double tessellation = 0;   ///< warm tessellation on one thread into one reused Mesh, s
  double freshTessellation = 0; ///< the same into a fresh Mesh each run (its pages faulted in), s
  double tessellationCpu = 0, batchPositionsCpu = 0, batchJetsCpu = 0; ///< the same figures on CPU time, s
  std::size_t planBytes = 0;
  double coldPlans = 0;      ///< face interiors with the ribbon tables ready but no plans, one thread, s
  std::size_t batchPoints = 0;
  double batchPositions = 0; ///< Surface::evaluatePositions at batchPoints random domain points, one thread, s
  double batchJets = 0;      ///< the same points with du, dv and normals (Surface::evaluate on spans), s
};

/// Random points inside each face's domain polygon, faces in turn.
std::vector<std::pair<int, Vec2>> randomDomainPoints(const Surface &surface, std::size_t count) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  std::vector<std::pair<int, Vec2>> samples;
  for (int k = 0; samples.size() < count; ++k) {
    const int face = k % surface.faceCount(), n = surface.domainSides(face);
    const Vec2 uv{coordinate(rng), coordinate(rng)};
    bool inside = true;
    for (int i = 0; i < n && inside; ++i) {
      const Vec2 p = surface.domainCorner(face, i), q = surface.domainCorner(face, i + 1);
      inside = cross(q - p, uv - p) > 0;
    }
    if (inside) samples.push_back({face, uv});
  }
  return samples;
}

/// Cold, warm and all-thread evaluation of face interiors on one thread, for
/// the given schemes. The schemes take turns within each round and each
/// figure is the fastest of its rounds, so slow spells of a shared machine
/// reach every scheme alike and the ratios between them stay meaningful.
void measureEvaluation(const Network &network, std::vector<SchemeFigures *> figures, int resolution, int threads,
                       int rounds) {
  std::vector<Surface> surfaces;
  for (SchemeFigures *f : figures) {
    f->cold = f->warm = f->warmThreads = f->coldPlans = INFINITY;
    surfaces.push_back(Surface::build(network, {f->scheme}));
  }
  // One output buffer, as a program evaluating repeatedly would keep: the
  // figures time evaluation, not allocating and clearing the output.
  std::vector<Vec3> points(faceInteriorPoints(surfaces.front(), resolution));
  auto seconds = [](auto &&run) {
    const auto t0 = Clock::now();
    run();
    return std::chrono::duration<double>(Clock::now() - t0).count();
  };
  for (int round = 0; round < rounds; ++round) {
    {
      tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
      for (std::size_t k = 0; k < figures.size(); ++k) {
        // Cold: a surface fresh from Surface::build (untimed) and no plans.
        const Surface fresh = Surface::build(network, surfaces[k].options());
        clearEvaluationPlans();
        figures[k]->cold = std::min(figures[k]->cold, seconds([&] {
          figures[k]->interiorPoints = evaluateFaceInteriors(fresh, points, {resolution, 1});
        }));
        figures[k]->planBytes = evaluationPlanCache().bytes; // this scheme's plans alone
        // Plans alone: the same surface again (its ribbon tables now built), the plans dropped.
        clearEvaluationPlans();
        figures[k]->coldPlans = std::min(figures[k]->coldPlans, seconds([&] {
          evaluateFaceInteriors(fresh, points, {resolution, 1});
        }));
      }
      for (const Surface &surface : surfaces) evaluateFaceInteriors(surface, points, {resolution, 1}); // plans again
      for (int repeat = 0; repeat < 2; ++repeat)
        for (std::size_t k = 0; k < figures.size(); ++k)
          figures[k]->warm = std::min(figures[k]->warm, seconds([&] { evaluateFaceInteriors(surfaces[k], points, {resolution, 1}); }));
    }
    // Untimed first: TBB's workers wake up (they sleep after the serial part).
    evaluateFaceInteriors(surfaces.front(), points, {resolution, threads});
    for (int repeat = 0; repeat < 2; ++repeat)
      for (std::size_t k = 0; k < figures.size(); ++k)
        figures[k]->warmThreads = std::min(figures[k]->warmThreads, seconds([&] {
          evaluateFaceInteriors(surfaces[k], points, {resolution, threads});
        }));
  }
}

/// Construction, pointwise evaluation and tessellation of one scheme (its
/// face-interior figures: measureEvaluation).
SchemeFigures measure(const Network &network, Scheme scheme, int resolution, int points) {
  SchemeFigures f;
  f.scheme = scheme, f.name = schemeName(scheme);
  std::optional<Surface> surface;
  f.build = fastest([&] { surface = Surface::build(network, {scheme}); });
  const std::vector<std::pair<int, Vec2>> samples = randomDomainPoints(*surface, static_cast<std::size_t>(points));
  // Batches at arbitrary points, as an embedding program makes them: one
  // span of random domain points per face.
  constexpr std::size_t kBatchPoints = 1 << 16;
  std::vector<std::vector<Vec2>> batches(static_cast<std::size_t>(surface->faceCount()));
  for (const auto &[face, uv] : randomDomainPoints(*surface, kBatchPoints)) batches[face].push_back(uv);
  std::vector<Vec3> positions(kBatchPoints);
  std::vector<SurfacePoint> jets(kBatchPoints);
  f.batchPoints = kBatchPoints;
  auto eachBatch = [&](auto &&evaluate) {
    for (int face = 0; face < surface->faceCount(); ++face) evaluate(face, std::span<const Vec2>(batches[face]));
  };
  eachBatch([&](int face, std::span<const Vec2> uv) { surface->evaluatePositions(face, uv, positions); }); // tables
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    f.pointwise = fastest([&] {
      double sum = 0;
      for (const auto &[face, uv] : samples) sum += surface->evaluate(face, uv).point.x;
      if (!std::isfinite(sum)) std::fprintf(stderr, "non-finite point\n");
    });
    // Into one mesh kept across runs, as the face-interior figures keep
    // one buffer: the figure times the tessellation, not the allocator and
    // the kernel faulting in ~70 bytes a point (the fresh figure has them).
    Mesh mesh;
    f.tessellation = fastest(
        [&] {
          tessellate(*surface, {resolution, 1}, mesh);
          f.meshPoints = mesh.positions.size();
        },
        3, &f.tessellationCpu);
    f.freshTessellation = fastest([&] { tessellate(*surface, {resolution, 1}); });
    f.batchPositions = fastest(
        [&] { eachBatch([&](int face, std::span<const Vec2> uv) { surface->evaluatePositions(face, uv, positions); }); },
        3, &f.batchPositionsCpu);
    f.batchJets = fastest([&] { eachBatch([&](int face, std::span<const Vec2> uv) { surface->evaluate(face, uv, jets); }); },
                          3, &f.batchJetsCpu);
  }
  return f;
}

} // namespace

nlohmann::json benchReport(const BenchOptions &options) {
  const Network network = Network::build(loadNetworkInput(options.input), options.input);
  const int threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
  std::vector<SchemeFigures> figures;
  for (Scheme s : {Scheme::GregoryG1, Scheme::GregoryG2, Scheme::CompositeRibbon})
    figures.push_back(measure(network, s, options.resolution, options.points));
  // The Gregory schemes' evaluation figures are compared with each
  // other: they are measured together, in turns. Composite-ribbon
  // (per sample, ~1 s a run) takes fewer rounds.
  measureEvaluation(network, {&figures[0], &figures[1]}, options.resolution, threads, 7);
  measureEvaluation(network, {&figures[2]}, options.resolution, threads, 3);
  const SchemeFigures &g1 = figures[0], &g2 = figures[1];
  auto perSecond = [](std::size_t n, double s) { return s > 0 ? n / s : 0.0; };
  nlohmann::json out;
  out["input"] = options.input;
  out["resolution"] = options.resolution;
  out["threads"] = threads;
  out["kernel_width"] = kernels::bestWidth().name + " (" + std::to_string(kernels::bestWidth().lanes) + " doubles)";
  out["g1_points_per_second_per_core"] = perSecond(g1.interiorPoints, g1.warm);
  out["g2_points_per_second_per_core"] = perSecond(g2.interiorPoints, g2.warm);
  out["g2_over_g1_eval_cost"] = g2.warm / g1.warm;
  out["g2_over_g1_pointwise_cost"] = g2.pointwise / g1.pointwise;
  out["g2_over_g1_build_cost"] = g2.build / g1.build;
  out["g2_over_g1_tessellation_cost"] = g2.tessellation / g1.tessellation;
  out["g2_positions_any_points_per_second_per_core"] = perSecond(g2.batchPoints, g2.batchPositions);
  out["g2_jets_any_points_per_second_per_core"] = perSecond(g2.batchPoints, g2.batchJets);
  out["g2_tessellation_points_per_second_per_core"] = perSecond(g2.meshPoints, g2.tessellation);
  out["g2_tessellation_fresh_mesh_points_per_second_per_core"] = perSecond(g2.meshPoints, g2.freshTessellation);
  // The one-thread figures on the thread's CPU time (information).
  out["g2_tessellation_points_per_cpu_second"] = perSecond(g2.meshPoints, g2.tessellationCpu);
  out["g2_positions_any_points_per_cpu_second"] = perSecond(g2.batchPoints, g2.batchPositionsCpu);
  out["g2_jets_any_points_per_cpu_second"] = perSecond(g2.batchPoints, g2.batchJetsCpu);
  out["warm_over_cold_speedup"] = g2.cold / g2.warm;
  out["thread_speedup"] = g2.warm / g2.warmThreads;
  // Plans built, per face-interior sample evaluated (on one-face
  // inputs such as the default: per plan sample).
  out["plan_build_ns_per_sample"] = (g2.coldPlans - g2.warm) / g2.interiorPoints * 1e9;
  out["cache_saved_fraction"] = (g2.cold - g2.warm) / g2.cold;
  for (const SchemeFigures &f : figures)
    out["schemes"][f.name] = {{"build_seconds", f.build},
                              {"pointwise_points", options.points},
                              {"pointwise_seconds", f.pointwise},
                              {"pointwise_points_per_second", perSecond(options.points, f.pointwise)},
                              {"evaluated_points", f.interiorPoints},
                              {"cold_seconds", f.cold},
                              {"warm_seconds", f.warm},
                              {"warm_threads_seconds", f.warmThreads},
                              {"warm_points_per_second_per_core", perSecond(f.interiorPoints, f.warm)},
                              {"mesh_points", f.meshPoints},
                              {"tessellation_seconds", f.tessellation},
                              {"tessellation_points_per_second", perSecond(f.meshPoints, f.tessellation)},
                              {"fresh_mesh_tessellation_seconds", f.freshTessellation},
                              {"plan_cache_bytes", f.planBytes},
                              {"plan_build_ns_per_sample", (f.coldPlans - f.warm) / f.interiorPoints * 1e9},
                              {"cache_saved_fraction", (f.cold - f.warm) / f.cold},
                              {"any_points", f.batchPoints},
                              {"positions_any_points_per_second", perSecond(f.batchPoints, f.batchPositions)},
                              {"jets_any_points_per_second", perSecond(f.batchPoints, f.batchJets)}};
  return out;
}

Command addBenchCommand(CLI::App &app) {
  struct Options {
    std::string input = "builtin:pentagon";
    int resolution = 256, points = 4000, threads = 0;
    bool json = false, quiet = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App *sub = app.add_subcommand("bench", "G1 vs G2 evaluation cost (Salvi and Varady 2014, Table 1 form)");
  sub->add_option("INPUT", o->input, "network file (.json, .lop) or builtin:NAME")->capture_default_str();
  sub->add_option("--resolution", o->resolution, "tessellation resolution")
      ->check(wholeNumberIn(1, 4096))
      ->capture_default_str();
  sub->add_option("--points", o->points, "random points for the pointwise evaluation")
      ->check(wholeNumberIn(1, 10000000))
      ->capture_default_str();
  addThreadsOption(sub, o->threads);
  sub->add_flag("--json", o->json, "print one JSON object");
  addQuietFlag(sub, o->quiet); // accepted everywhere; bench shows no progress line
  return {sub, [o] {
            const nlohmann::json out = benchReport({o->input, o->resolution, o->points, o->threads});
            if (o->json) {
              std::printf("%s\n", out.dump(2).c_str());
              return 0;
            }
            const int threads = out["threads"];
            std::printf("%s, resolution %d, %d threads, kernels %s\n\n", o->input.c_str(), o->resolution, threads,
                        out["kernel_width"].get<std::string>().c_str());
            std::printf("%-17s %9s %11s %11s %9s %9s %9s %10s %13s %11s %13s\n", "scheme", "build ms",
                        ("eval " + std::to_string(o->points) + " ms").c_str(), "pointwise/s", "points", "cold ms",
                        "warm ms", "warm Nt ms", "warm pts/s/core", "tess. ms", "tess. pts/s");
            for (Scheme scheme : {Scheme::GregoryG1, Scheme::GregoryG2, Scheme::CompositeRibbon}) {
              const nlohmann::json &f = out["schemes"][schemeName(scheme)];
              auto ms = [&](const char *key) { return f[key].get<double>() * 1e3; };
              auto number = [&](const char *key) { return f[key].get<double>(); };
              std::printf("%-17s %9.2f %11.2f %11.3g %9zu %9.2f %9.2f %10.2f %13.3g %11.2f %13.3g\n",
                          schemeName(scheme).c_str(), ms("build_seconds"), ms("pointwise_seconds"),
                          number("pointwise_points_per_second"), f["evaluated_points"].get<std::size_t>(),
                          ms("cold_seconds"), ms("warm_seconds"), ms("warm_threads_seconds"),
                          number("warm_points_per_second_per_core"), ms("tessellation_seconds"),
                          number("tessellation_points_per_second"));
            }
            std::printf("\nG2/G1 cost: build %.2f, pointwise %.2f, warm evaluation %.2f, tessellation %.2f\n",
                        out["g2_over_g1_build_cost"].get<double>(), out["g2_over_g1_pointwise_cost"].get<double>(),
                        out["g2_over_g1_eval_cost"].get<double>(), out["g2_over_g1_tessellation_cost"].get<double>());
            std::printf("G2 warm over cold: %.2fx; %d threads over 1: %.2fx\n",
                        out["warm_over_cold_speedup"].get<double>(), threads, out["thread_speedup"].get<double>());
            std::printf("G2 at %zu random domain points, one thread: positions %.3g/s, with du, dv, normals %.3g/s\n",
                        out["schemes"]["gregory-g2"]["any_points"].get<std::size_t>(),
                        out["g2_positions_any_points_per_second_per_core"].get<double>(),
                        out["g2_jets_any_points_per_second_per_core"].get<double>());
            return 0;
          }};
}

} // namespace curvenet::cli
