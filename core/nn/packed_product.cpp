#include "nn/packed_product.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace motionstyle::nn {
namespace {

namespace ei = Eigen::internal;
using Eigen::Index;

// The right-hand side is packed and multiplied in panels of this many columns, so that its packed
// copy (depth x columns) stays in the L2 cache for channel counts up to a few hundred.
constexpr Index kColumnsPerPanel = 256;

template <typename S>
struct Kernel {
  using Traits = ei::gebp_traits<S, S>;
  using LhsMapper = ei::const_blas_data_mapper<S, Index, Eigen::ColMajor>;
  using RhsMapper = ei::const_blas_data_mapper<S, Index, Eigen::ColMajor>;
  using ResMapper = ei::blas_data_mapper<S, Index, Eigen::ColMajor, Eigen::Unaligned, 1>;
  using PackLhs = ei::gemm_pack_lhs<S, Index, LhsMapper, Traits::mr, Traits::LhsProgress,
                                    typename Traits::LhsPacket4Packing, Eigen::ColMajor>;
  using PackRhs = ei::gemm_pack_rhs<S, Index, RhsMapper, Traits::nr, Eigen::ColMajor>;
  using Gebp = ei::gebp_kernel<S, S, Index, ResMapper, Traits::mr, Traits::nr, false, false>;
};

}  // namespace

template <typename S>
void PackedMatrix<S>::pack(const S* a, Index rows, Index depth) {
  if (a == nullptr || rows < 1 || depth < 1)
    throw std::invalid_argument("PackedMatrix: expected a matrix of at least 1 x 1, got " + std::to_string(rows) +
                                " x " + std::to_string(depth));
  rows_ = rows;
  depth_ = depth;
  packed_.resize(static_cast<std::size_t>(rows * depth));
  typename Kernel<S>::PackLhs pack_lhs;
  pack_lhs(packed_.data(), typename Kernel<S>::LhsMapper(a, rows), depth, rows);
}

template <typename S>
void PackedMatrix<S>::multiplyInto(const S* b, Index b_stride, Index cols, S* out, Index out_stride,
                                   Scratch& scratch) const {
  if (packed_.empty()) throw std::logic_error("PackedMatrix: multiplyInto() before pack()");
  if (cols < 0 || b_stride < depth_ || out_stride < rows_)
    throw std::invalid_argument("PackedMatrix: " + std::to_string(cols) + " columns with strides " +
                                std::to_string(b_stride) + " / " + std::to_string(out_stride) + " for a " +
                                std::to_string(rows_) + " x " + std::to_string(depth_) + " matrix");
  typename Kernel<S>::PackRhs pack_rhs;
  typename Kernel<S>::Gebp gebp;
  for (Index first = 0; first < cols; first += kColumnsPerPanel) {
    const Index panel = std::min(kColumnsPerPanel, cols - first);
    scratch.resize(static_cast<std::size_t>(depth_ * panel));
    pack_rhs(scratch.data(), typename Kernel<S>::RhsMapper(b + first * b_stride, b_stride), depth_, panel);
    S* destination = out + first * out_stride;
    for (Index j = 0; j < panel; ++j) std::fill_n(destination + j * out_stride, rows_, S(0));
    gebp(typename Kernel<S>::ResMapper(destination, out_stride), packed_.data(), scratch.data(), rows_, depth_, panel,
         S(1));
  }
}

template class PackedMatrix<float>;
template class PackedMatrix<double>;

}  // namespace motionstyle::nn
