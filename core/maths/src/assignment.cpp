// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/assignment.hpp"

#include <limits>

namespace colortrack {

std::vector<int> solveAssignment(const cv::Mat &costIn) {
  CV_Assert(costIn.type() == CV_64FC1);
  const bool transposed = costIn.rows > costIn.cols;
  const cv::Mat cost = transposed ? cv::Mat(costIn.t()) : costIn;
  const int n = cost.rows, m = cost.cols;  // n <= m
  std::vector<int> rowOf(m + 1, 0);        // rowOf[j]: 1-based row assigned to column j (0 = none)
  if (n > 0) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    std::vector<double> u(n + 1, 0), v(m + 1, 0);
    std::vector<int> way(m + 1, 0);
    // Rows enter one at a time; each grows the matching by a shortest augmenting path in reduced costs
    // (Dijkstra over columns, column 0 standing for the new row), keeping the potentials feasible.
    for (int i = 1; i <= n; ++i) {
      rowOf[0] = i;
      int j0 = 0;
      std::vector<double> minv(m + 1, inf);
      std::vector<char> used(m + 1, 0);
      do {
        used[j0] = 1;
        const int i0 = rowOf[j0];
        double delta = inf;
        int j1 = 0;
        const double *row = cost.ptr<double>(i0 - 1);
        for (int j = 1; j <= m; ++j) {
          if (used[j]) continue;
          const double reduced = row[j - 1] - u[i0] - v[j];
          if (reduced < minv[j]) {
            minv[j] = reduced;
            way[j] = j0;
          }
          if (minv[j] < delta) {
            delta = minv[j];
            j1 = j;
          }
        }
        for (int j = 0; j <= m; ++j) {
          if (used[j]) {
            u[rowOf[j]] += delta;
            v[j] -= delta;
          } else {
            minv[j] -= delta;
          }
        }
        j0 = j1;
      } while (rowOf[j0] != 0);
      do {  // flip the augmenting path
        const int j1 = way[j0];
        rowOf[j0] = rowOf[j1];
        j0 = j1;
      } while (j0 != 0);
    }
  }
  std::vector<int> columnOfRow(n, -1);
  for (int j = 1; j <= m; ++j)
    if (rowOf[j] > 0) columnOfRow[rowOf[j] - 1] = j - 1;
  if (!transposed) return columnOfRow;
  std::vector<int> result(costIn.rows, -1);  // rows of the input were columns of the solved matrix
  for (int r = 0; r < n; ++r)
    if (columnOfRow[r] >= 0) result[columnOfRow[r]] = r;
  return result;
}

}  // namespace colortrack
