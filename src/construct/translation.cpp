#include "volspline/construct/translation.h"

#include <cmath>
#include <string>
#include <vector>

#include "volspline/core/error.h"

namespace volspline {

BSplineVolume translation_volume(const BSplineSurface& F, const BSplineCurve& K) {
  if (F.dimension() != K.dimension())
    throw InvalidInput("the path lies in R^" + std::to_string(K.dimension()) + " but the surface in R^" +
                           std::to_string(F.dimension()),
                       "path");
  const int dim = F.dimension();
  const bool rational = F.is_rational() || K.is_rational();
  const int cs = dim + (rational ? 1 : 0);
  // K(w_min), not K_0: an unclamped path does not start at its first control point.
  const Eigen::VectorXd start = K.evaluate({K.domain_min(0)});
  const int nf = F.num_control_points_total(), nk = K.num_control_points_total();
  const int fcs = F.coefficient_size(), kcs = K.coefficient_size();
  const auto& fh = F.homogeneous();
  const auto& kh = K.homogeneous();
  std::vector<double> coefficients(static_cast<std::size_t>(nf) * static_cast<std::size_t>(nk) * static_cast<std::size_t>(cs));
  for (int k = 0; k < nk; ++k) {
    const double* kc = kh.data() + static_cast<std::size_t>(k) * static_cast<std::size_t>(kcs);
    const double kw = K.is_rational() ? kc[dim] : 1.0;
    for (int ij = 0; ij < nf; ++ij) {
      const double* fc = fh.data() + static_cast<std::size_t>(ij) * static_cast<std::size_t>(fcs);
      const double fw = F.is_rational() ? fc[dim] : 1.0;
      // eq. 6 with M_k built from the translate of K starting at K(w_min): the homogeneous
      // numerator of F(u,v) + K(w) - start over the product of the two denominators is
      // F_num K_den + F_den (K_num - start K_den), separately in each parameter; it holds for
      // weight-0 coefficients (directions) of either factor as well.
      double* out = coefficients.data() + (static_cast<std::size_t>(ij) + static_cast<std::size_t>(nf) * static_cast<std::size_t>(k)) *
                                              static_cast<std::size_t>(cs);
      for (int c = 0; c < dim; ++c) out[c] = fc[c] * kw + fw * (kc[c] - start[c] * kw);
      if (rational) out[dim] = fw * kw;
    }
  }
  return BSplineVolume::from_homogeneous({F.knot_vector(0), F.knot_vector(1), K.knot_vector(0)}, dim, rational,
                                         std::move(coefficients));
}

BSplineVolume extrude(const BSplineSurface& F, const Eigen::Vector3d& vector) {
  if (F.dimension() != 3)
    throw InvalidInput("extrusion needs a surface in R^3, got one in R^" + std::to_string(F.dimension()), "profile");
  if (!vector.allFinite() || vector.norm() == 0.0)
    throw InvalidInput("the extrusion vector must be finite and nonzero", "vector");
  // Lasser's n = 1 case: a degree-1 path from the origin, so V_ij1 = F_ij + T.
  const BSplineCurve path({KnotVector::bezier(1)}, 3, {0.0, 0.0, 0.0, vector.x(), vector.y(), vector.z()});
  return translation_volume(F, path);
}

}  // namespace volspline
