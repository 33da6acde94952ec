#include <limits>
#include <vector>

#include "roadslam/objects/tracker.h"

namespace roadslam::objects {
namespace {

/// Kuhn-Munkres with potentials, O(n^2 m) for n <= m rows (the e-maxx formulation): the column of each row.
std::vector<int> assignRows(const std::vector<std::vector<double>>& a, size_t n, size_t m) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(n + 1, 0), v(m + 1, 0);
  std::vector<size_t> p(m + 1, 0), way(m + 1, 0);
  for (size_t i = 1; i <= n; ++i) {
    p[0] = i;
    size_t j0 = 0;
    std::vector<double> minv(m + 1, inf);
    std::vector<char> used(m + 1, false);
    do {
      used[j0] = true;
      const size_t i0 = p[j0];
      double delta = inf;
      size_t j1 = 0;
      for (size_t j = 1; j <= m; ++j) {
        if (used[j]) continue;
        const double cur = a[i0 - 1][j - 1] - u[i0] - v[j];
        if (cur < minv[j]) minv[j] = cur, way[j] = j0;
        if (minv[j] < delta) delta = minv[j], j1 = j;
      }
      for (size_t j = 0; j <= m; ++j) {
        if (used[j]) {
          u[p[j]] += delta, v[j] -= delta;
        } else {
          minv[j] -= delta;
        }
      }
      j0 = j1;
    } while (p[j0] != 0);
    do {
      const size_t j1 = way[j0];
      p[j0] = p[j1];
      j0 = j1;
    } while (j0);
  }
  std::vector<int> row(n, -1);
  for (size_t j = 1; j <= m; ++j) {
    if (p[j]) row[p[j] - 1] = static_cast<int>(j - 1);
  }
  return row;
}

}  // namespace

std::vector<int> hungarian(const std::vector<std::vector<double>>& cost) {
  const size_t n = cost.size(), m = n ? cost[0].size() : 0;
  if (!n || !m) return std::vector<int>(n, -1);
  if (n <= m) return assignRows(cost, n, m);
  std::vector<std::vector<double>> t(m, std::vector<double>(n));
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = 0; j < m; ++j) t[j][i] = cost[i][j];
  }
  const auto col = assignRows(t, m, n);
  std::vector<int> row(n, -1);
  for (size_t j = 0; j < m; ++j) {
    if (col[j] >= 0) row[static_cast<size_t>(col[j])] = static_cast<int>(j);
  }
  return row;
}

}  // namespace roadslam::objects
