#include "volspline/simplex/adaptive_refinement.h"

#include <algorithm>
#include <chrono>
#include <numeric>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "volspline/core/error.h"
#include "volspline/simplex/dms_spline_evaluator.h"
#include "volspline/simplex/knot_clouds.h"

namespace volspline {

std::string refinement_stop_text(RefinementStop stop) {
  switch (stop) {
    case RefinementStop::NotRequested: return "not requested (no error bound)";
    case RefinementStop::Converged: return "converged: every tetrahedron below the error bound";
    case RefinementStop::TetrahedronBudget: return "stopped: the tetrahedron budget is reached";
    case RefinementStop::TimeBudget: return "stopped: the time budget is spent";
    case RefinementStop::RoundBudget: return "stopped: the round budget is reached";
    case RefinementStop::ErrorIncreased: return "stopped: the last round raised the total error and was undone";
    case RefinementStop::NoValidSplit: return "stopped: no split gave valid knot clouds";
    case RefinementStop::TooFewPoints: return "stopped: more control vectors than data points would follow";
  }
  return "?";
}

double mean_normalised_field_error(const VolumeFitErrors& errors) {
  double sum = 0;
  for (const auto& f : errors.attributes) sum += f.normalised_mean_square;
  return errors.attributes.empty() ? 0 : sum / static_cast<double>(errors.attributes.size());
}

TetrahedronFitErrors tetrahedron_fit_errors(const DmsSplineVolume& volume, const VolumeData& data) {
  const std::size_t k = data.attribute_names.size();
  std::vector<int> columns;
  for (const auto& name : data.attribute_names) columns.push_back(volume.attribute_column(name));
  std::vector<double> range(k, 1);
  for (std::size_t a = 0; a < k; ++a) {
    const auto column = data.attributes.col(static_cast<Eigen::Index>(a));
    const double r = column.size() ? column.maxCoeff() - column.minCoeff() : 0;
    range[a] = r > 0 ? r : 1;
  }
  // Per point (in parallel, one evaluator per thread): its tetrahedron, squared normalised error
  // (mean over attributes) and normalised gradient magnitude.
  std::vector<int> tetrahedron(data.size(), -1);
  std::vector<double> square(data.size(), 0), steepness(data.size(), 0);
  const DmsSplineEvaluator prototype(volume);
  tbb::enumerable_thread_specific<DmsSplineEvaluator> evaluators(prototype);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, data.size(), 256), [&](const tbb::blocked_range<std::size_t>& block) {
    DmsSplineEvaluator& evaluator = evaluators.local();
    DmsSplinePoint p;
    for (std::size_t i = block.begin(); i != block.end(); ++i) {
      evaluator.evaluate(data.points[i], 1, p);
      if (!p.inside) continue;
      tetrahedron[i] = p.tetrahedron;
      for (std::size_t a = 0; a < k; ++a) {
        const double e = (p.value[columns[a]] - data.attributes(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(a))) / range[a];
        square[i] += e * e / static_cast<double>(k);
        steepness[i] += p.gradient.row(columns[a]).norm() / range[a];
      }
    }
  });
  const std::size_t tetrahedra = volume.domain().tetrahedra.size();
  TetrahedronFitErrors out;
  out.points.assign(tetrahedra, 0);
  out.rms.assign(tetrahedra, 0);
  out.steepest.assign(tetrahedra, Eigen::Vector3d::Zero());
  std::vector<double> best(tetrahedra, -1);
  for (std::size_t i = 0; i < data.size(); ++i) {
    const int t = tetrahedron[i];
    if (t < 0) continue;
    const auto u = static_cast<std::size_t>(t);
    ++out.points[u];
    out.rms[u] += square[i];
    if (steepness[i] > best[u]) best[u] = steepness[i], out.steepest[u] = data.points[i];
  }
  out.point_tetrahedron = std::move(tetrahedron);
  for (std::size_t t = 0; t < tetrahedra; ++t)
    if (out.points[t] > 0) out.rms[t] = std::sqrt(out.rms[t] / static_cast<double>(out.points[t]));
  return out;
}

namespace {

// The volume with the listed tetrahedra split 1 → 4 at their points (each corner in turn replaced
// by the point, so all stay positively oriented). Clouds: the old ones kept, generated clouds for
// the new vertices; where that fails eq. 3 or the non-degeneracy checks, the generated clouds of
// the split tetrahedra's corners too; failing that, all generated. The attributes start as the old
// spline at the new control points' domain points (the refit's prior).
DmsSplineVolume refinement_split(const DmsSplineVolume& volume, const std::vector<int>& split, const std::vector<Eigen::Vector3d>& at,
                                 double spread) {
  TetrahedralMesh domain = volume.domain();
  std::vector<bool> touched(domain.points.size(), false);
  for (std::size_t s = 0; s < split.size(); ++s) {
    const auto t = static_cast<std::size_t>(split[s]);
    const std::array<int, 4> old = domain.tetrahedra[t];
    const int x = static_cast<int>(domain.points.size());
    domain.points.push_back(at[s]);
    for (int v : old) touched[static_cast<std::size_t>(v)] = true;
    domain.tetrahedra[t] = {x, old[1], old[2], old[3]};
    domain.tetrahedra.push_back({old[0], x, old[2], old[3]});
    domain.tetrahedra.push_back({old[0], old[1], x, old[3]});
    domain.tetrahedra.push_back({old[0], old[1], old[2], x});
  }
  touched.resize(domain.points.size(), true);
  const int n = volume.degree();
  const auto per = static_cast<std::size_t>(n + 1);
  KnotCloudOptions cloud_options;
  cloud_options.spread = spread;
  const KnotClouds generated = generate_knot_clouds(domain, n, cloud_options);
  const auto mixed = [&](bool take_touched) {
    KnotClouds clouds = generated;
    for (std::size_t v = 0; v < volume.domain().points.size(); ++v)
      if (!(take_touched && touched[v]))
        std::copy(volume.knots().knots.begin() + static_cast<std::ptrdiff_t>(v * per),
                  volume.knots().knots.begin() + static_cast<std::ptrdiff_t>((v + 1) * per), clouds.knots.begin() + static_cast<std::ptrdiff_t>(v * per));
    return clouds;
  };
  KnotClouds clouds = generated;
  for (bool take_touched : {false, true}) {
    KnotClouds candidate = mixed(take_touched);
    try {
      validate_knot_clouds(domain, candidate);
      clouds = std::move(candidate);
      break;
    } catch (const InvalidInput&) {
    }
  }
  DmsSplineVolume refined(std::move(domain), std::move(clouds), volume.sharing(), volume.attribute_names());
  DmsSplineEvaluator old(volume);
  for (int r = 0; r < refined.control_vector_count(); ++r) {
    const DmsSplinePoint p = old.evaluate(refined.domain_point(r));
    if (p.inside) refined.control_vectors().row(r).tail(refined.dimension() - 3) = p.value.tail(refined.dimension() - 3).transpose();
  }
  return refined;
}

}  // namespace

AdaptiveRefinementReport refine_volume_fit(DmsSplineVolume& volume, VolumeFitErrors& errors, const VolumeData& data,
                                           const AdaptiveRefinementOptions& options, const ControlVectorFitOptions& fit_options,
                                           const std::function<void(const RefinementRound&)>& after_round) {
  AdaptiveRefinementReport report;
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  TetrahedronFitErrors local = tetrahedron_fit_errors(volume, data);
  const auto above_count = [&](const TetrahedronFitErrors& e) {
    return static_cast<std::size_t>(std::count_if(e.rms.begin(), e.rms.end(), [&](double r) { return r > options.error; }));
  };
  RefinementRound first;
  first.tetrahedra = volume.domain().tetrahedra.size();
  first.control_points = static_cast<std::size_t>(volume.control_vector_count());
  first.field_mean_square = mean_normalised_field_error(errors);
  first.largest_tetrahedron_error = local.rms.empty() ? 0 : *std::max_element(local.rms.begin(), local.rms.end());
  report.rounds.push_back(first);
  if (!(options.error > 0)) {
    report.above = 0;
    return report;
  }
  const std::size_t max_tetrahedra = options.max_tetrahedra > 0 ? options.max_tetrahedra : 8 * first.tetrahedra;
  ControlVectorFitOptions refit = fit_options;
  refit.prior_from_volume = true;
  const double spread = options.spread;
  for (;;) {
    const std::size_t above = above_count(local);
    report.above = above;
    if (above == 0) {
      report.stop = RefinementStop::Converged;
      break;
    }
    if (static_cast<int>(report.rounds.size()) > options.max_rounds) {
      report.stop = RefinementStop::RoundBudget;
      break;
    }
    if (options.seconds > 0 && elapsed() >= options.seconds) {
      report.stop = RefinementStop::TimeBudget;
      break;
    }
    const std::size_t tetrahedra = volume.domain().tetrahedra.size();
    if (tetrahedra + 3 > max_tetrahedra) {
      report.stop = RefinementStop::TetrahedronBudget;
      break;
    }
    // The worst tetrahedra first, as many as the budget allows (ties: the lower index).
    std::vector<int> order;
    for (std::size_t t = 0; t < tetrahedra; ++t)
      if (local.rms[t] > options.error) order.push_back(static_cast<int>(t));
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return local.rms[static_cast<std::size_t>(a)] > local.rms[static_cast<std::size_t>(b)]; });
    order.resize(std::min(order.size(), (max_tetrahedra - tetrahedra) / 3));
    std::vector<Eigen::Vector3d> at;
    for (int t : order) {
      const auto& tet = volume.domain().tetrahedra[static_cast<std::size_t>(t)];
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      for (int v : tet) centroid += volume.domain().points[static_cast<std::size_t>(v)] / 4;
      at.push_back(0.5 * (local.steepest[static_cast<std::size_t>(t)] + centroid));
    }
    const auto round_start = std::chrono::steady_clock::now();
    RefinementRound round;
    round.above = above;
    round.split = order.size();
    DmsSplineVolume refined = [&] {
      try {
        return refinement_split(volume, order, at, spread);
      } catch (const InvalidInput&) {
        return DmsSplineVolume(volume);
      }
    }();
    if (refined.domain().tetrahedra.size() == tetrahedra) {
      report.stop = RefinementStop::NoValidSplit;
      break;
    }
    VolumeFitErrors refined_errors;
    try {
      refined_errors = fit_control_vectors(refined, data, refit);
    } catch (const InvalidInput&) {
      report.stop = RefinementStop::TooFewPoints;
      break;
    }
    round.tetrahedra = refined.domain().tetrahedra.size();
    round.control_points = static_cast<std::size_t>(refined.control_vector_count());
    round.field_mean_square = mean_normalised_field_error(refined_errors);
    round.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - round_start).count();
    if (round.field_mean_square > report.rounds.back().field_mean_square) {
      round.undone = true;
      round.largest_tetrahedron_error = report.rounds.back().largest_tetrahedron_error;
      report.rounds.push_back(round);
      if (after_round) after_round(round);
      report.stop = RefinementStop::ErrorIncreased;
      break;
    }
    volume = std::move(refined);
    errors = std::move(refined_errors);
    local = tetrahedron_fit_errors(volume, data);
    round.largest_tetrahedron_error = *std::max_element(local.rms.begin(), local.rms.end());
    report.rounds.push_back(round);
    if (after_round) after_round(round);
  }
  return report;
}

}  // namespace volspline
