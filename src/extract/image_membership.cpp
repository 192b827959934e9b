#include "volspline/extract/image_membership.h"

#include "volspline/analysis/point_in_image.h"

namespace volspline {

template <int D>
ImageMembershipTest image_membership_test(const SplineImage<D>& image) {
  return [&image](const Eigen::Vector3d& x) -> std::optional<bool> {
    // The last preimage this thread found, and of which image (a test of another image, or an
    // image made later at the same address, must not use it: the search runs then).
    struct Hint {
      const SplineImage<D>* image = nullptr;
      std::uint64_t generation = 0;
      typename SplineImage<D>::Preimage preimage;
    };
    thread_local Hint hint;
    const typename SplineImage<D>::Query q =
        hint.image == &image && hint.generation == image.generation() ? image.query(x, hint.preimage) : image.query(x);
    if (q.preimage) hint = {&image, image.generation(), *q.preimage};
    switch (q.membership) {
      case ImageMembership::Inside: return true;
      case ImageMembership::Outside: return false;
      case ImageMembership::Undecided: break;
    }
    return std::nullopt;
  };
}

template ImageMembershipTest image_membership_test<3>(const SplineImage<3>&);
template ImageMembershipTest image_membership_test<4>(const SplineImage<4>&);

}  // namespace volspline
