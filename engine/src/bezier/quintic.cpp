#include "bezier/quintic.hpp"

#include <cmath>

namespace curvenet {
inline namespace v1 {
namespace bezier {

double binomial(int n, int k) {
  if (k < 0 || k > n) return 0;
  double r = 1;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

void bernstein(int n, double t, double *values, double *derivatives) {
  const double s = 1 - t;
  for (int i = 0; i <= n; ++i) values[i] = binomial(n, i) * std::pow(t, i) * std::pow(s, n - i);
  if (!derivatives) return;
  for (int i = 0; i <= n; ++i) {
    // d/dt B_i^n = n (B_{i−1}^{n−1} − B_i^{n−1})
    const double a = i > 0 ? binomial(n - 1, i - 1) * std::pow(t, i - 1) * std::pow(s, n - i) : 0.0;
    const double b = i < n ? binomial(n - 1, i) * std::pow(t, i) * std::pow(s, n - 1 - i) : 0.0;
    derivatives[i] = n * (a - b);
  }
}

QuinticPatch::Point QuinticPatch::evaluate(double u, double v) const {
  double bu[6], du[6], bv[6], dv[6];
  bernstein(5, u, bu, du);
  bernstein(5, v, bv, dv);
  Point p;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      p.point += (bu[i] * bv[j]) * net[i][j];
      p.du += (du[i] * bv[j]) * net[i][j];
      p.dv += (bu[i] * dv[j]) * net[i][j];
    }
  return p;
}

std::array<int, 2> QuinticPatch::sideIndex(int side, int along, int depth) {
  switch (side & 3) {
  case 0: return {along, depth};
  case 1: return {5 - depth, along};
  case 2: return {5 - along, 5 - depth};
  default: return {depth, 5 - along};
  }
}

std::vector<Vec3> elevate(const std::vector<Vec3> &p) {
  const int n = static_cast<int>(p.size()) - 1;
  std::vector<Vec3> q(n + 2);
  q[0] = p[0];
  q[n + 1] = p[n];
  for (int i = 1; i <= n; ++i) q[i] = (double(i) / (n + 1)) * p[i - 1] + (1 - double(i) / (n + 1)) * p[i];
  return q;
}

std::vector<std::vector<double>> restrictionMatrix(int n, double a, double b) {
  // Blossom: the piece's control point m is the blossom at (a^{n−m}, b^m),
  // evaluated on unit coefficient vectors.
  std::vector<std::vector<double>> R(n + 1, std::vector<double>(n + 1, 0.0));
  for (int m = 0; m <= n; ++m) {
    std::vector<std::vector<double>> level(n + 1, std::vector<double>(n + 1, 0.0));
    for (int k = 0; k <= n; ++k) level[k][k] = 1;
    for (int r = 1; r <= n; ++r) {
      const double t = r <= n - m ? a : b;
      for (int k = 0; k + r <= n; ++k)
        for (int c = 0; c <= n; ++c) level[k][c] = (1 - t) * level[k][c] + t * level[k + 1][c];
    }
    R[m] = level[0];
  }
  return R;
}

void fillCoonsInterior(QuinticPatch &patch) {
  auto &b = patch.net;
  for (int i = 1; i < 5; ++i)
    for (int j = 1; j < 5; ++j) {
      const double u = i / 5.0, v = j / 5.0;
      b[i][j] = (1 - u) * b[0][j] + u * b[5][j] + (1 - v) * b[i][0] + v * b[i][5] -
                ((1 - u) * (1 - v) * b[0][0] + u * (1 - v) * b[5][0] + (1 - u) * v * b[0][5] + u * v * b[5][5]);
    }
}

} // namespace bezier
} // namespace v1
} // namespace curvenet
