#pragma once
// Blending volumes (Lasser 1994, eq. 7): ruled volumes between two surfaces and lofts
// (skinning) through several, after making the surfaces compatible.
#include <vector>

#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// Makes every section a spline on the same knot vectors (hence the same degrees and control
/// point counts) without changing its geometry: each section is clamped, its domain mapped
/// affinely onto [0,1] x [0,1] (a knot t becomes (t - a) / (b - a)), its degrees raised to the
/// largest among the sections (elevate_degree), and the union of all knot vectors (largest
/// multiplicity of each value) inserted (refine_knots). Knot values closer than 1e-12 after the
/// map are taken as one (the value of the first section that has it): moving a knot by a
/// rounding error moves the surface by a rounding error. If any section is rational, all become
/// rational (weight 1 for polynomial ones). An empty or one-element list is only clamped and
/// reparameterised. \throw InvalidInput (where() "sections[i]") if the sections lie in spaces
/// of different dimensions.
void make_compatible(std::vector<BSplineSurface>& sections);

/// The ruled (linear blending) volume V(u,v,w) = (1 - w) a(u,v) + w b(u,v), w in [0, 1], of the
/// compatible forms of a and b (make_compatible, so u and v run over [0, 1]). Its control
/// points are eq. 7 with n = 1. For rational surfaces the blend is taken in homogeneous space:
/// every w-line is still the straight segment from a(u,v) to b(u,v), traversed linearly when
/// the weights of a and b agree there.
/// \throw InvalidInput as make_compatible.
BSplineVolume ruled_volume(const BSplineSurface& a, const BSplineSurface& b);

/// How the loft assigns a w parameter to each section.
enum class LoftParameterization {
  /// Cumulative distances between corresponding control points, averaged over the net.
  ChordLength,
  /// Cumulative square roots of those distances, averaged (smoother for uneven spacing).
  Centripetal,
};

/// The w parameters in [0, 1] at which loft() interpolates `sections`, which must already be
/// compatible: for each control point index, the normalised cumulative (chord length or
/// centripetal) distances through the sections, averaged over the indices whose points move.
/// Distances are taken between the homogeneous coefficients, the space the loft interpolates
/// in. \throw InvalidInput (where() "sections[i]") if the sections are not compatible or two
/// consecutive sections have identical control nets.
std::vector<double> loft_parameters(const std::vector<BSplineSurface>& sections,
                                    LoftParameterization parameterization = LoftParameterization::ChordLength);

/// Skinning: the volume of degree min(degree_w, n - 1) in w that interpolates the n sections,
/// V(u, v, t_k) = section_k(u, v) on [0,1]^2 after make_compatible, with t_k from
/// loft_parameters and the clamped knot vector by averaging of the t_k (Piegl-Tiller eq. 9.8),
/// so the collocation matrix is nonsingular (Schoenberg-Whitney). Each control point row across
/// the sections is interpolated by solving that one system (one LU factorisation, every
/// coordinate a right-hand side). Rational sections are lofted in homogeneous space: the
/// interpolated quantity is (w x, w), so the sections are interpolated exactly, but between
/// them the weights are interpolated too.
/// \throw InvalidInput (where() "sections") for fewer than 2 sections, ("degree") for
/// degree_w < 1, as make_compatible and loft_parameters, and ("sections") if interpolating
/// rational sections makes a weight negative.
BSplineVolume loft(const std::vector<BSplineSurface>& sections, int degree_w,
                   LoftParameterization parameterization = LoftParameterization::ChordLength);

}  // namespace volspline
