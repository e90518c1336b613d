// Curve evaluation cost: the innermost operation of ribbon construction.
// Names say degree and what is evaluated; the counter is points per second.
#include <benchmark/benchmark.h>

#include <cmath>

#include "curvenet/curve.hpp"

namespace {

curvenet::BSplineCurve sampleCurve(int degree, int points) {
  std::vector<curvenet::Vec3> controls;
  for (int i = 0; i < points; ++i) controls.push_back({double(i), std::sin(i * 0.7), std::cos(i * 0.3)});
  std::vector<double> params;
  for (int i = 0; i < points; ++i) params.push_back(double(i) / (points - 1));
  return curvenet::BSplineCurve::interpolate(degree, params, controls);
}

void BM_CurveDerivatives(benchmark::State &state) {
  const auto curve = sampleCurve(static_cast<int>(state.range(0)), 24);
  double t = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(curve.derivatives(t));
    t += 0.0137;
    if (t > 1) t -= 1;
  }
  state.counters["points/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_CurveDerivatives)->ArgName("degree")->Arg(3)->Arg(5)->Arg(7);

// The basis-function algorithm (Piegl & Tiller A2.3) the Taylor form replaced.
void BM_CurveDerivativesReference(benchmark::State &state) {
  const auto curve = sampleCurve(static_cast<int>(state.range(0)), 24);
  double t = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(curve.derivativesReference(t));
    t += 0.0137;
    if (t > 1) t -= 1;
  }
  state.counters["points/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_CurveDerivativesReference)->ArgName("degree")->Arg(3)->Arg(5)->Arg(7);

// Sorted parameters in one call: one span search per run of samples in a span.
void BM_CurveDerivativesBatch(benchmark::State &state) {
  const auto curve = sampleCurve(static_cast<int>(state.range(0)), 24);
  std::vector<double> t(1024);
  for (std::size_t k = 0; k < t.size(); ++k) t[k] = double(k) / double(t.size() - 1);
  std::vector<std::array<curvenet::Vec3, 4>> out(t.size());
  for (auto _ : state) {
    curve.derivatives(t, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["points/s"] = benchmark::Counter(static_cast<double>(state.iterations() * t.size()),
                                                  benchmark::Counter::kIsRate);
}
BENCHMARK(BM_CurveDerivativesBatch)->ArgName("degree")->Arg(3)->Arg(5)->Arg(7);

} // namespace
