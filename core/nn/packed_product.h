#pragma once
// A fixed left-hand matrix kept in the panel layout of Eigen's matrix-product kernel, so that
// products with it pay no copy of it.
//
// CONTRACT. pack(a, rows, depth) stores A (rows x depth, column-major, leading dimension `rows`).
// multiplyInto(b, b_stride, cols, out, out_stride) then computes
//     out = A * B        (out: rows x cols, B: depth x cols, both column-major)
// with the same kernel, and so the same numbers, as Eigen's `out.noalias() = A * B`.
//
// WHY. Eigen's GEMM copies both operands into its panel layout at every product. When B has few
// columns (a spectral layer's segments of a short clip: 6 for 240 frames) copying A costs as much as
// multiplying by it: 24 % of a 960-frame stylize (docs/decisions.md, "Short clips in the spectral
// layers"). A kernel spectrum that is multiplied thousands of times is packed once instead.
//
// Built on Eigen 3.4's internal gemm_pack_lhs, gemm_pack_rhs and gebp_kernel (the three steps of
// its own GEMM, GeneralMatrixMatrix.h): the packed layout depends on the build's vector width, so a
// packed matrix lives in memory only, never in a file. tests/unit/nn compare it with Eigen's product.
//
// Thread safety: multiplyInto() is const and reads only the packed matrix: any number of threads may
// call it at once, each with its own scratch.

#include <Eigen/Core>
#include <vector>

namespace motionstyle::nn {

template <typename S>
class PackedMatrix {
 public:
  // Scratch for one thread's products (the right-hand side in the kernel's layout): reused across calls.
  using Scratch = std::vector<S, Eigen::aligned_allocator<S>>;

  // rows, depth >= 1; `a` holds rows * depth values. Throws std::invalid_argument otherwise.
  void pack(const S* a, Eigen::Index rows, Eigen::Index depth);

  Eigen::Index rows() const { return rows_; }
  Eigen::Index depth() const { return depth_; }
  bool empty() const { return packed_.empty(); }

  // out = A * B (see above). cols >= 0; b_stride >= depth(); out_stride >= rows(). Needs pack() first.
  void multiplyInto(const S* b, Eigen::Index b_stride, Eigen::Index cols, S* out, Eigen::Index out_stride,
                    Scratch& scratch) const;

 private:
  Eigen::Index rows_ = 0, depth_ = 0;
  std::vector<S, Eigen::aligned_allocator<S>> packed_;
};

}  // namespace motionstyle::nn
