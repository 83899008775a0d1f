/// \file hausdorff.cpp
/// Hausdorff distance (14) and Prop. 2's K with nanoflann k-d trees.

#include "reach_trajopt/reach/hausdorff.h"

#include <cstdint>
#include <memory>
#include <nanoflann.hpp>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

namespace {

/// nanoflann dataset adaptor over the columns of a column-major matrix.
struct ColumnCloud {
  const double* data;
  int dim;
  int count;
  std::size_t kdtree_get_point_count() const { return static_cast<std::size_t>(count); }
  double kdtree_get_pt(std::size_t i, std::size_t d) const {
    return data[i * static_cast<std::size_t>(dim) + d];
  }
  template <class Bbox>
  bool kdtree_get_bbox(Bbox&) const {
    return false;
  }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, ColumnCloud>,
                                                 ColumnCloud, -1, std::uint32_t>;

/// Nearest neighbour of q in the tree (squared distance), excluding index `skip`.
void nearest(const Tree& tree, const double* q, int skip, std::uint32_t& index, double& dist2) {
  std::uint32_t idx[2];
  double d2[2];
  const std::size_t k = tree.knnSearch(q, skip >= 0 ? 2 : 1, idx, d2);
  index = static_cast<std::uint32_t>(-1);
  dist2 = HUGE_VAL;
  for (std::size_t i = 0; i < k; ++i) {
    if (static_cast<int>(idx[i]) == skip) continue;
    if (d2[i] < dist2 || (d2[i] == dist2 && idx[i] < index)) {
      dist2 = d2[i];
      index = idx[i];
    }
  }
}

}  // namespace

SetDistance hausdorffDistance(const Eigen::Ref<const Eigen::MatrixXd>& A_in,
                              const Eigen::Ref<const Eigen::MatrixXd>& B_in) {
  if (A_in.rows() != B_in.rows())
    throw ReachError("hausdorffDistance: the sets have different dimensions");
  requireFinite("hausdorffDistance: A", A_in);
  requireFinite("hausdorffDistance: B", B_in);
  // Contiguous copies (Ref may have an outer stride).
  const Eigen::MatrixXd A = A_in, B = B_in;
  const int dim = static_cast<int>(A.rows());
  SetDistance out;
  if (A.cols() == 0 || B.cols() == 0) return out;
  const ColumnCloud ca{A.data(), dim, static_cast<int>(A.cols())};
  const ColumnCloud cb{B.data(), dim, static_cast<int>(B.cols())};
  const nanoflann::KDTreeSingleIndexAdaptorParams params(10);
  Tree ta(dim, ca, params), tb(dim, cb, params);
  ta.buildIndex();
  tb.buildIndex();
  std::uint32_t idx;
  double d2;
  double ab = 0.0, ba = 0.0, ka = 0.0, kb = 0.0;
  for (int i = 0; i < A.cols(); ++i) {
    nearest(tb, A.col(i).data(), -1, idx, d2);
    ab = std::max(ab, d2);
    if (d2 < out.closest) {
      out.closest = d2;
      out.closest_a = i;
      out.closest_b = static_cast<int>(idx);
    }
    if (A.cols() > 1) {
      nearest(ta, A.col(i).data(), i, idx, d2);
      ka = std::max(ka, d2);
    }
  }
  for (int j = 0; j < B.cols(); ++j) {
    nearest(ta, B.col(j).data(), -1, idx, d2);
    ba = std::max(ba, d2);
    if (B.cols() > 1) {
      nearest(tb, B.col(j).data(), j, idx, d2);
      kb = std::max(kb, d2);
    }
  }
  out.a_to_b = std::sqrt(ab);
  out.b_to_a = std::sqrt(ba);
  out.hausdorff = std::max(out.a_to_b, out.b_to_a);
  out.closest = std::sqrt(out.closest);
  if (A.cols() > 1) out.resolution_a = std::sqrt(ka);
  if (B.cols() > 1) out.resolution_b = std::sqrt(kb);
  return out;
}

}  // namespace reach_trajopt
