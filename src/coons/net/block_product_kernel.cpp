// One instance of block_product, multiply_<set>, per build of this file (src/CMakeLists.txt):
// COONS_BLOCK_PRODUCT_SET undefined is the baseline, with the build's own Eigen; avx2 and avx512
// are compiled with their instruction-set flags and Eigen's namespace renamed (coons_eigen_<set>),
// so that every Eigen template this file instantiates is a symbol of its own that the linker never
// merges with the SSE2 instance of the same template elsewhere. Those builds also let Eigen align
// its GEMM buffers itself (EIGEN_MALLOC_ALREADY_ALIGNED 0): the 1 of the rest of the build
// promises 16-byte blocks, and the wider packets need 32 or 64. And they take the GEMM path for
// every size (EIGEN_GEMM_TO_COEFFBASED_THRESHOLD 0): Eigen evaluates small products coefficient by
// coefficient, peeling the first entries of each column up to the destination's next 32- or 64-byte
// boundary and summing those in another order, so their last bits followed where malloc had put the
// block (a study sharded in three processes differed from the unsharded one); GEMM's and GEMV's
// order of summation depends on the sizes alone (test `block_product: the same bits wherever the
// blocks lie in memory`). The baseline keeps Eigen's defaults, as the rest of the build sees them:
// at 16 bytes every block BandedGram hands it starts on the same boundary.
#include "coons/net/block_product_kernel.h"

#ifdef COONS_BLOCK_PRODUCT_SET
#define COONS_JOIN_(a, b) a##b
#define COONS_JOIN(a, b) COONS_JOIN_(a, b)
#define Eigen COONS_JOIN(coons_eigen_, COONS_BLOCK_PRODUCT_SET)  // NOLINT(cppcoreguidelines-macro-usage)
#define COONS_MULTIPLY COONS_JOIN(multiply_, COONS_BLOCK_PRODUCT_SET)
#undef EIGEN_MALLOC_ALREADY_ALIGNED
#define EIGEN_MALLOC_ALREADY_ALIGNED 0
#define EIGEN_GEMM_TO_COEFFBASED_THRESHOLD 0
#else
#define COONS_MULTIPLY multiply_baseline
#endif

#include <Eigen/Core>
#include <cassert>

namespace coons::block_product_detail {

void COONS_MULTIPLY(ConstBlockView a, ConstBlockView b, bool transpose_b, BlockView out) {
  using Stride = Eigen::OuterStride<>;
  using ConstMap = Eigen::Map<const Eigen::MatrixXd, Eigen::Unaligned, Stride>;
  using Map = Eigen::Map<Eigen::MatrixXd, Eigen::Unaligned, Stride>;
  const ConstMap A(a.data, a.rows, a.cols, Stride(a.stride)), B(b.data, b.rows, b.cols, Stride(b.stride));
  Map C(out.data, out.rows, out.cols, Stride(out.stride));
  assert(C.rows() == A.rows());
  if (transpose_b) {
    assert(A.cols() == B.cols() && C.cols() == B.rows());
    C.noalias() = A * B.transpose();
  } else {
    assert(A.cols() == B.rows() && C.cols() == B.cols());
    C.noalias() = A * B;
  }
}

}  // namespace coons::block_product_detail
