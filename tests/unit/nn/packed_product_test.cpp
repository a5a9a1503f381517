// PackedMatrix: invalid use first, then its product against the plain triple sum in double (shapes
// that are not multiples of the kernel's panels, strided operands, zero columns and more columns than
// one right-hand panel), and against Eigen's own product in float.

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "gradient_check.h"
#include "nn/packed_product.h"

namespace motionstyle::nn {
namespace {

using test::MatD;
using test::randomMatrix;

TEST(PackedMatrix, RejectsAnEmptyMatrixAndUseBeforePacking) {
  PackedMatrix<double> packed;
  PackedMatrix<double>::Scratch scratch;
  const MatD a = MatD::Ones(3, 2);
  EXPECT_THROW(packed.pack(a.data(), 0, 2), std::invalid_argument);
  EXPECT_THROW(packed.pack(a.data(), 3, 0), std::invalid_argument);
  EXPECT_THROW(packed.pack(nullptr, 3, 2), std::invalid_argument);
  MatD out(3, 1);
  EXPECT_THROW(packed.multiplyInto(a.data(), 2, 1, out.data(), 3, scratch), std::logic_error);
  packed.pack(a.data(), 3, 2);
  EXPECT_THROW(packed.multiplyInto(a.data(), 1, 1, out.data(), 3, scratch), std::invalid_argument);  // b stride < depth
  EXPECT_THROW(packed.multiplyInto(a.data(), 2, 1, out.data(), 2, scratch), std::invalid_argument);  // out stride < rows
  EXPECT_THROW(packed.multiplyInto(a.data(), 2, -1, out.data(), 3, scratch), std::invalid_argument);
}

// out(i, j) = sum_k a(i, k) b(k, j), written out.
MatD tripleSum(const MatD& a, const MatD& b) {
  MatD out = MatD::Zero(a.rows(), b.cols());
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = 0; j < b.cols(); ++j)
      for (Eigen::Index k = 0; k < a.cols(); ++k) out(i, j) += a(i, k) * b(k, j);
  return out;
}

TEST(PackedMatrix, MultipliesLikeTheTripleSumForAnyShapeAndStride) {
  std::mt19937 rng(5);
  PackedMatrix<double>::Scratch scratch;
  for (const auto& [rows, depth, cols] : {std::tuple{1, 1, 1}, {7, 3, 5}, {33, 17, 6}, {128, 128, 24}, {25, 9, 300},
                                          {12, 40, 0}, {3, 1, 513}}) {
    const MatD a = randomMatrix(rows, depth, rng);
    const MatD b_strided = randomMatrix(depth + 3, cols, rng);  // B is its first `depth` rows
    const MatD b = b_strided.topRows(depth);
    PackedMatrix<double> packed;
    packed.pack(a.data(), rows, depth);
    EXPECT_EQ(packed.rows(), rows);
    EXPECT_EQ(packed.depth(), depth);
    MatD out = MatD::Constant(rows + 2, cols, 99.0);  // written rows only: the last two stay 99
    packed.multiplyInto(b_strided.data(), depth + 3, cols, out.data(), rows + 2, scratch);
    const MatD expected = tripleSum(a, b);
    SCOPED_TRACE(testing::Message() << rows << " x " << depth << " times " << cols << " columns");
    if (cols > 0) {
      EXPECT_LT((out.topRows(rows) - expected).cwiseAbs().maxCoeff(), 1e-12 * depth);
    }
    EXPECT_TRUE((out.bottomRows(2).array() == 99.0).all());
  }
}

TEST(PackedMatrix, OverwritesWhatTheOutputHeldAndIsReusable) {
  std::mt19937 rng(6);
  const Mat<float> a = randomMatrix(128, 128, rng).cast<float>();
  PackedMatrix<float> packed;
  packed.pack(a.data(), 128, 128);
  PackedMatrix<float>::Scratch scratch;
  for (int cols : {6, 24, 360}) {
    const Mat<float> b = randomMatrix(128, cols, rng).cast<float>();
    Mat<float> out = Mat<float>::Constant(128, cols, 1e6f);
    packed.multiplyInto(b.data(), 128, cols, out.data(), 128, scratch);
    const Mat<float> eigen = a * b;
    EXPECT_LT((out - eigen).cwiseAbs().maxCoeff(), 1e-4f * eigen.cwiseAbs().maxCoeff()) << cols << " columns";
  }
}

}  // namespace
}  // namespace motionstyle::nn
