#pragma once
// The membership test the trimmers contour (extract/image_contouring.h, superset_trimming.h):
// a certified point-in-image test (analysis/point_in_image.h) as true (inside), false (outside)
// or nothing (undecided). Grid corners and edge probes come in spatial order, so each thread
// remembers the last preimage it found and starts the next query with Newton from it
// (SplineImage::query with a hint): an inside corner next to an inside corner then costs a few
// Newton steps instead of a search, with the same acceptance criterion; outside and undecided
// answers still come from the full search.
#include "volspline/extract/superset_trimming.h"

namespace volspline {

template <int D>
class SplineImage;

/// The test of `image`, which must outlive it. Safe to call from many threads at once.
template <int D>
ImageMembershipTest image_membership_test(const SplineImage<D>& image);

}  // namespace volspline
