#pragma once
// A knot vector of a B-spline basis of degree p, with the evaluation of that basis.
// Domain and evaluation conventions: core/conventions.h.
#include <vector>

namespace volspline {

class KnotVector {
 public:
  /// \throw InvalidInput (where() = "[i]" for the offending knot) if degree < 1, if a knot is
  /// NaN or infinite, if knots decrease, if a knot's multiplicity exceeds degree + 1, if there
  /// are fewer than 2(degree + 1) knots, or if the domain [t_p, t_{m-p}] is empty.
  KnotVector(int degree, std::vector<double> knots);

  /// The knot vector of a Bézier segment on [a, b]: p+1 copies of a, then p+1 copies of b.
  /// \throw InvalidInput as the constructor (degree < 1, a or b not finite, or a >= b).
  static KnotVector bezier(int degree, double a = 0.0, double b = 1.0);
  /// Clamped, uniformly spaced interior knots: `spans` equal spans on [a, b].
  /// \throw InvalidInput if spans < 1, or as the constructor (degree < 1, a or b not finite, or
  /// a >= b).
  static KnotVector uniform_clamped(int degree, int spans, double a = 0.0, double b = 1.0);

  int degree() const { return degree_; }
  const std::vector<double>& knots() const { return knots_; }
  /// Number of basis functions (= control points in this direction): m - p where m + 1 knots.
  int num_basis() const { return static_cast<int>(knots_.size()) - degree_ - 1; }
  double domain_min() const { return knots_[degree_]; }
  double domain_max() const { return knots_[knots_.size() - degree_ - 1]; }
  bool contains(double t) const { return t >= domain_min() && t <= domain_max(); }
  /// True if the first and last p+1 knots are equal (the curve interpolates its end points).
  bool is_clamped() const;
  /// True if the knot vector is that of a single Bézier segment (clamped, no interior knots).
  bool is_bezier() const;

  /// The span index s with t_s <= t < t_{s+1} and p <= s < num_basis(); at the domain maximum
  /// the last nonempty span. t must lie in the domain (not checked: callers check once).
  int find_span(double t) const;
  /// The span whose closure contains t from the left: the nonempty span s with
  /// t_s < t <= t_{s+1}; at the domain minimum the first nonempty span. Evaluating `basis` on it
  /// gives the left limit, which differs from find_span only at knots of multiplicity p + 1.
  int find_span_left(double t) const;
  /// The p+1 basis functions N_{s-p..s}(t) that may be nonzero on span s.
  void basis(int span, double t, double* values) const;
  /// The p+1 basis functions and their first derivatives: values[0..p], then derivatives
  /// values[p+1..2p+1]; as cheap as `basis` (the derivatives fall out of its last step).
  void basis_first_derivatives(int span, double t, double* values) const;
  /// Basis functions and their derivatives up to `order`: values[k * (p+1) + j] is the k-th
  /// derivative of N_{s-p+j}(t). Derivatives above p are zero.
  void basis_derivatives(int span, double t, int order, double* values) const;

  /// Distinct knot values in the domain, ascending (the breakpoints).
  std::vector<double> breakpoints() const;
  /// Number of nonempty spans in the domain.
  int num_spans() const { return static_cast<int>(breakpoints().size()) - 1; }
  /// Multiplicity of the knot value t (0 if t is not a knot).
  int multiplicity(double t) const;
  /// The Greville abscissae g_i = (t_{i+1} + ... + t_{i+p}) / p, one per basis function: the
  /// coefficients with which the basis reproduces the linear function t (Marsden's identity),
  /// so control points placed at them give the identity map; i / p on the Bézier segment [0, 1].
  std::vector<double> greville_abscissae() const;

  friend bool operator==(const KnotVector& a, const KnotVector& b) {
    return a.degree_ == b.degree_ && a.knots_ == b.knots_;
  }

 private:
  int degree_;
  std::vector<double> knots_;
  // 1 / (t_{s+i+1} - t_{s+1-j+i}) for every span s, j = 1..p, i < j: the denominators of the
  // Cox-de Boor triangle depend on the knots only, and divisions dominate evaluation otherwise.
  std::vector<double> inverse_differences_;
  const double* inverse_differences(int span) const {
    return inverse_differences_.data() + static_cast<std::size_t>(span - degree_) * static_cast<std::size_t>(degree_ * (degree_ + 1) / 2);
  }
};

}  // namespace volspline
