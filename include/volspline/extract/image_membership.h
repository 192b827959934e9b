#pragma once
// The membership test the trimmers contour (extract/image_contouring.h, superset_trimming.h):
// a certified point-in-image test (analysis/point_in_image.h) as true (inside), false (outside)
// or nothing (undecided). Grid corners and edge probes come in spatial order, so each thread
// remembers the last preimage it found and starts the next query with Newton from it
// (SplineImage::query with a hint): an inside corner next to an inside corner then costs a few
// Newton steps instead of a search, with the same acceptance criterion; outside and undecided
// answers still come from the full search.
#include <array>
#include <vector>

#include "volspline/extract/superset_trimming.h"
#include "volspline/mesh/triangle_mesh.h"

namespace volspline {

template <int D>
class SplineImage;

/// The test of `image`, which must outlive it. Safe to call from many threads at once.
template <int D>
ImageMembershipTest image_membership_test(const SplineImage<D>& image);

/// Makes each vertex's tag (its patch of `image` and parameters) map within `distance` of the
/// vertex: a tag that maps farther (interpolated in a superset triangle, a crease point's) is
/// replaced by a preimage near the vertex (SplineImage::preimage_near from the tag; else the
/// membership search's preimage of the vertex; else, for a vertex just outside the image, from
/// the preimages of points 2 and 8 distances inwards along its normal). `mesh` must be
/// outward-oriented for the last. Sets stats.tags_corrected, tags_beyond_tolerance (tags no
/// attempt could mend, left as they were) and largest_tag_distance (docs/envelopes.md, "Vertex
/// tags"). \throw InvalidInput if the sizes differ from the mesh's vertices or a patch does not
/// exist.
template <int D>
void correct_vertex_tags(const SplineImage<D>& image, const TriangleMesh& mesh, std::vector<std::array<double, D>>& parameters,
                         std::vector<int>& patches, double distance, SupersetTrimmingStats& stats);

}  // namespace volspline
