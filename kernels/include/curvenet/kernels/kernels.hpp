// curvenet/kernels/kernels.hpp — batched evaluation kernels over many samples.
//
// Every kernel is one template over the SIMD width (DESIGN.md §4, STYLE.md
// practice 5). The width-1 instance is the scalar reference; the other
// instances are compiled for each instruction set the build supports and
// chosen at run time for the CPU (Google Highway's dynamic dispatch). This
// header is the only view of the kernels: it names no SIMD library, so no
// engine code depends on one.
//
// Data are structures of arrays: a batch of `count` Dual numbers (value and
// the two partial derivatives over the domain) is three arrays; a batch of
// Dual 3-vectors is nine. Arrays need no alignment; output arrays may not
// alias inputs unless stated.
//
// Threads: every kernel is a pure function of its arguments; calls on
// disjoint outputs may run concurrently. Cost: linear in `count`, no
// allocation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace curvenet {
inline namespace v1 {
namespace kernels {

/// One SIMD width the kernels can run at on this CPU.
struct Width {
  /// Opaque selector passed to the kernels; kBestWidth picks the widest the
  /// CPU supports, kScalarReference the width-1 reference.
  std::int64_t id;
  std::string name; ///< instruction set, e.g. "AVX2"; "scalar" for the reference
  std::size_t lanes; ///< doubles per vector
};
constexpr std::int64_t kBestWidth = 0;
constexpr std::int64_t kScalarReference = -1;

/// The scalar reference first, then every compiled instruction set this CPU
/// runs, widest first. Thread-safe.
std::vector<Width> availableWidths();
/// The width kBestWidth resolves to on this CPU.
Width bestWidth();

/// Batch of Dual numbers (read-only).
struct DualSpan {
  const double *v, *du, *dv;
};
/// Batch of Dual 3-vectors: component c of the value is v[c][k], of ∂/∂u du[c][k], …
struct DualVec3Span {
  double *v[3], *du[3], *dv[3];
};
struct ConstDualVec3Span {
  const double *v[3], *du[3], *dv[3];
};
/// Per-sample ribbon data along one side, at each sample's side parameter:
/// P, T (and C for parabolic ribbons) with their side-parameter derivatives.
/// C and dC null for linear ribbons.
struct RibbonJets {
  const double *P[3], *dP[3], *T[3], *dT[3];
  const double *C[3] = {nullptr, nullptr, nullptr}, *dC[3] = {nullptr, nullptr, nullptr};
};

/// (b) Ribbon points with exact first derivatives:
/// out[k] = P(σ_k) + δ_k T(σ_k) [+ ½ δ_k² C(σ_k)], where the jets are taken at
/// σ_k's value and σ, δ carry their domain derivatives (chain rule).
void ribbonPoints(std::size_t count, const RibbonJets &jets, DualSpan sigma, DualSpan delta, DualVec3Span out,
                  std::int64_t width = kBestWidth);

/// (a) Weighted accumulation, out[k] += w[k] · x[k] in Dual arithmetic
/// (value, ∂u, ∂v by the product rule). out may not alias x.
void accumulate(std::size_t count, DualSpan w, ConstDualVec3Span x, DualVec3Span out,
                std::int64_t width = kBestWidth);
/// (a) Weighted accumulation of one constant vector, out[k] += w[k] · c.
void accumulateConstant(std::size_t count, DualSpan w, const double c[3], DualVec3Span out,
                        std::int64_t width = kBestWidth);

/// Constants of one side of a regular domain for the cubic Hermite sweepline
/// (paper 000 eq. 20) in that side's frame (side from (0,0) to (1,0), domain
/// at y > 0): a, b the directions of the neighbouring sides leaving the two
/// ends; apex the intersection of their lines (the radial sweep's centre),
/// or parallel = true when they do not meet (n = 4).
struct SweepFrame {
  double ax, ay, bx, by;
  double apexX = 0, apexY = 0;
  bool parallel = false;
};

/// (c) Sweepline roots for arbitrary points (x, y) of a side frame: the s ∈
/// [0, 1] with F(s) = (x − s) w_y(s) − y w_x(s) = 0, w = a H(s) + b H(1 − s),
/// H(s) = 2s³ − 3s² + 1 — a quartic. All roots on [0, 1] are isolated (the
/// derivative cascade F'' → F' → F splits [0, 1] into monotone pieces, each
/// refined by bisection and Newton); among those with d ≥ 0 the
/// orientation-preserving one nearest the radial parameter wins (the rule of
/// the engine's scalar solver); points on no sweepline get clamp(x, 0, 1).
/// Writes s and the distance parameter d with (x, y) = (s, 0) + d w(s).
void hermiteSweepRoots(std::size_t count, const SweepFrame &frame, const double *x, const double *y, double *s,
                       double *d, std::int64_t width = kBestWidth);

} // namespace kernels
} // namespace v1
} // namespace curvenet
