#pragma once
// The parts of a mesh: what each triangle is a piece of, as one table of numbers, names and
// colours. The number is what a mesh stores (TriangleMesh::parts) and what files carry (the PLY
// face property `part`, the OBJ groups `part_N`); the colour is what the renderer
// (render/mesh_renderer.h) and the glTF writer (mesh/mesh_writer.h) draw it in.
//
//  number  part             name              colour (sRGB)
//   0..5   UMin..WMax       u_min..w_max      the boundary faces u, v, w = min, max (Joy–Duchaineau
//                                             1999 §4, the parametric part of the boundary): blue,
//                                             green, purple; darker at min, lighter at max
//   6      JacobianZero     jacobian_zero     the implicit surface det J = 0 (Theorem 4.1):
//                                             orange-red, the thing one looks for
//   7..9   IsoU..IsoW       iso_u..iso_w      isoparametric surfaces u, v, w = const (Lasser 1994
//                                             §IV): the mid tones of the faces' colours
//   10     Slice            slice             planar slices: sand, like a cut through material
//   11     BlendSpline      blend_spline      a box-spline blend's zero set inside the box (Peters–
//                                             Wittman 1995 §6): orange, the blend one looks at
//   12     BlendPrimitive   blend_primitive   the primitives' own surface outside the box: grey
//   13     SweepCap         sweep_cap         a swept solid's envelope (Conkey–Joy 2000 §3): the
//                                             generator's boundary at t = 0 or t = 1: steel blue
//   14     SweepFace        sweep_face        the envelope swept by the generator's faces and
//                                             edges (their images and characteristic surfaces):
//                                             teal
//   15     SweepRankDeficient sweep_rank_deficient  where J123 = J124 = J134 = J234 = 0 inside
//                                             the 4-dimensional domain: magenta
//   16     AttributeIsosurface attribute_isosurface  where an attribute of a simplex spline volume
//                                             takes a value (Hua–He–Qin §6.2): amber
//   17     DomainBoundary   domain_boundary   the boundary of a simplex spline volume's domain
//                                             mapped by its geometry: pale grey-blue
//
// Numbers 0..10 are those of every mesh file volspline has written; a number not in the table (a
// file may carry any) is drawn grey.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include <Eigen/Core>

namespace volspline {

/// A mesh part; the enumerator's value is the part number.
enum class Part : std::uint8_t {
  UMin = 0,
  UMax = 1,
  VMin = 2,
  VMax = 3,
  WMin = 4,
  WMax = 5,
  JacobianZero = 6,
  IsoU = 7,
  IsoV = 8,
  IsoW = 9,
  Slice = 10,
  BlendSpline = 11,
  BlendPrimitive = 12,
  SweepCap = 13,
  SweepFace = 14,
  SweepRankDeficient = 15,
  AttributeIsosurface = 16,
  DomainBoundary = 17,
};

/// One row of the part table.
struct PartInfo {
  Part part;
  /// Lower case, underscores: a name for a legend or a file.
  std::string_view name;
  /// sRGB, components in [0, 1].
  std::array<double, 3> srgb;
};

/// Every part, in the order of its number (kParts[n].part has number n).
inline constexpr std::array<PartInfo, 18> kParts{{
    {Part::UMin, "u_min", {0.26, 0.47, 0.82}},             // blue
    {Part::UMax, "u_max", {0.55, 0.72, 0.95}},             // light blue
    {Part::VMin, "v_min", {0.30, 0.66, 0.38}},             // green
    {Part::VMax, "v_max", {0.64, 0.85, 0.52}},             // light green
    {Part::WMin, "w_min", {0.55, 0.40, 0.78}},             // purple
    {Part::WMax, "w_max", {0.80, 0.70, 0.95}},             // lavender
    {Part::JacobianZero, "jacobian_zero", {0.95, 0.33, 0.12}},  // orange-red
    {Part::IsoU, "iso_u", {0.36, 0.58, 0.90}},             // the u faces' blue
    {Part::IsoV, "iso_v", {0.45, 0.76, 0.45}},             // green
    {Part::IsoW, "iso_w", {0.68, 0.55, 0.88}},             // purple
    {Part::Slice, "slice", {0.93, 0.76, 0.45}},            // sand
    {Part::BlendSpline, "blend_spline", {0.95, 0.33, 0.12}},  // orange, as the blend pictures always were
    {Part::BlendPrimitive, "blend_primitive", {0.70, 0.70, 0.70}},  // grey
    {Part::SweepCap, "sweep_cap", {0.42, 0.55, 0.72}},     // steel blue
    {Part::SweepFace, "sweep_face", {0.25, 0.68, 0.66}},   // teal
    {Part::SweepRankDeficient, "sweep_rank_deficient", {0.85, 0.25, 0.65}},  // magenta
    {Part::AttributeIsosurface, "attribute_isosurface", {0.98, 0.70, 0.20}},  // amber
    {Part::DomainBoundary, "domain_boundary", {0.72, 0.76, 0.84}},  // pale grey-blue
}};

/// The colour of numbers not in the table.
inline constexpr std::array<double, 3> kUnknownPartSrgb{0.70, 0.70, 0.70};

/// The part number of triangles whose mesh file names no part (STL, a PLY face without `part`,
/// OBJ faces outside a `part_N` group): 0, the number of Part::UMin, as readers always gave.
inline constexpr int kUnnamedPartNumber = 0;

/// The number a mesh stores for `part`.
constexpr int part_number(Part part) { return static_cast<int>(part); }

/// The face of the domain where parameter `direction` (0 = u, 1 = v, 2 = w) is at its minimum
/// (at_max false) or maximum: UMin, UMax, ..., WMax.
constexpr Part face_part(int direction, bool at_max) { return static_cast<Part>(2 * direction + (at_max ? 1 : 0)); }

/// The isoparametric surfaces where parameter `direction` is constant: IsoU, IsoV, IsoW.
constexpr Part isoparametric_part(int direction) { return static_cast<Part>(part_number(Part::IsoU) + direction); }

/// The table row of part number `number`, or null for a number not in the table.
constexpr const PartInfo* part_info(int number) {
  return number >= 0 && number < static_cast<int>(kParts.size()) ? &kParts[static_cast<std::size_t>(number)] : nullptr;
}

/// The sRGB colour, components in [0, 1], of part number `number` (kParts), grey
/// (kUnknownPartSrgb) for a number not in the table.
Eigen::Vector3d part_color(int number);
inline Eigen::Vector3d part_color(Part part) { return part_color(part_number(part)); }

/// The name of part number `number` (kParts), or "part_N" for a number not in the table.
std::string part_name(int number);

}  // namespace volspline
