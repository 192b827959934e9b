#include "volume_fitting_assembly.h"

#include <algorithm>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "volspline/simplex/dms_spline_evaluator.h"

namespace volspline {

Eigen::SparseMatrix<double, Eigen::RowMajor> parallel_basis_matrix(const DmsSplineVolume& volume, const std::vector<Eigen::Vector3d>& points) {
  constexpr std::size_t block = 256;
  const std::size_t blocks = (points.size() + block - 1) / block;
  const DmsSplineEvaluator prototype(volume);  // compiles every tetrahedron's plan once; copies share it
  tbb::enumerable_thread_specific<DmsSplineEvaluator> evaluators(prototype);
  // Per block: the (column, value) pairs of its points, and where each point's pairs end.
  std::vector<std::vector<std::pair<int, double>>> entries(blocks);
  std::vector<std::vector<int>> ends(blocks);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    DmsSplineEvaluator& evaluator = evaluators.local();
    auto& e = entries[b];
    auto& end = ends[b];
    std::vector<std::pair<int, double>> row;
    for (std::size_t i = b * block; i < std::min(points.size(), (b + 1) * block); ++i) {
      row.clear();
      evaluator.for_each_collocation_weight(points[i], [&](int column, double value) {
        if (value != 0) row.emplace_back(column, value);
      });
      // A shared control row appears once per tetrahedron around its domain point: the values
      // are summed in the order found (stable sort by column), so rounding does not depend on
      // the threads.
      std::stable_sort(row.begin(), row.end(), [](const auto& p, const auto& q) { return p.first < q.first; });
      for (std::size_t k = 0; k < row.size(); ++k) {
        if (k > 0 && row[k].first == row[k - 1].first)
          e.back().second += row[k].second;
        else
          e.push_back(row[k]);
      }
      end.push_back(static_cast<int>(e.size()));
    }
  });
  Eigen::SparseMatrix<double, Eigen::RowMajor> a(static_cast<Eigen::Index>(points.size()), volume.control_vector_count());
  std::size_t nonzeros = 0;
  for (const auto& e : entries) nonzeros += e.size();
  a.resizeNonZeros(static_cast<Eigen::Index>(nonzeros));
  int* outer = a.outerIndexPtr();
  int* inner = a.innerIndexPtr();
  double* values = a.valuePtr();
  std::size_t at = 0, row = 0;
  outer[0] = 0;
  for (std::size_t b = 0; b < blocks; ++b) {
    std::size_t begin = 0;
    for (const int end : ends[b]) {
      for (std::size_t k = begin; k < static_cast<std::size_t>(end); ++k, ++at) {
        inner[at] = entries[b][k].first;
        values[at] = entries[b][k].second;
      }
      begin = static_cast<std::size_t>(end);
      outer[++row] = static_cast<int>(at);
    }
  }
  return a;
}

}  // namespace volspline
