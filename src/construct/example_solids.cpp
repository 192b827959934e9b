#include "volspline/construct/example_solids.h"

#include <cmath>
#include <numbers>

#include "volspline/core/error.h"

namespace volspline {

BSplineVolume bent_tricubic_volume() {
  const KnotVector ku = KnotVector::uniform_clamped(3, 3), kv = KnotVector::uniform_clamped(3, 2),
                   kw = KnotVector::bezier(3);
  std::vector<double> p;
  const int nu = ku.num_basis(), nv = kv.num_basis(), nw = kw.num_basis();
  for (int k = 0; k < nw; ++k)
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i) {
        const double x = 4.0 * i / (nu - 1), y = 1.5 * j / (nv - 1), z = 1.0 * k / (nw - 1);
        const double bulge = (k == nw - 1 && i > 0 && i < nu - 1 && j > 0 && j < nv - 1) ? 0.6 : 0.0;
        p.insert(p.end(), {x, y, z + 0.12 * x * x + bulge});
      }
  return BSplineVolume({ku, kv, kw}, 3, std::move(p));
}

BSplineVolume twisted_volume(double turns) {
  const KnotVector k1 = KnotVector::bezier(1), kw = KnotVector::bezier(3);
  std::vector<double> p;
  for (int k = 0; k < 4; ++k) {
    const double angle = 2.0 * std::numbers::pi * turns * k / 3.0, c = std::cos(angle), s = std::sin(angle);
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const double x = i - 0.5, y = j - 0.5;
        p.insert(p.end(), {c * x - s * y, s * x + c * y, 1.0 * k});
      }
  }
  return BSplineVolume({k1, k1, kw}, 3, std::move(p));
}

BSplineVolume half_cylinder_shell(double inner, double outer, double height) {
  if (!(inner >= 0.0 && inner < outer && height > 0.0))
    throw InvalidInput("a cylinder shell needs 0 <= inner < outer and height > 0");
  // Angular control points (Lasser Theorem 2, alpha = pi): (r, 0), direction (0, r) at
  // infinity, (-r, 0) with weights 1, 0, 1; radial and axial directions are linear.
  std::vector<double> p, w;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 2; ++i) {
        const double r = i == 0 ? inner : outer, z = k * height;
        if (j == 0) p.insert(p.end(), {r, 0.0, z}), w.push_back(1.0);
        if (j == 1) p.insert(p.end(), {0.0, r, 0.0}), w.push_back(0.0);  // a direction: no z offset
        if (j == 2) p.insert(p.end(), {-r, 0.0, z}), w.push_back(1.0);
      }
  return BSplineVolume({KnotVector::bezier(1), KnotVector::bezier(2), KnotVector::bezier(1)}, 3, std::move(p), std::move(w));
}

}  // namespace volspline
