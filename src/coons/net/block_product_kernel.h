// The per-instruction-set instances of block_product (block_product_kernel.cpp, compiled once per
// set). Internal to block_product.cpp and its test; this header includes no Eigen.
#pragma once

#include "coons/net/block_product.h"

namespace coons::block_product_detail {

void multiply_baseline(ConstBlockView a, ConstBlockView b, bool transpose_b, BlockView out);
void multiply_avx2(ConstBlockView a, ConstBlockView b, bool transpose_b, BlockView out);
void multiply_avx512(ConstBlockView a, ConstBlockView b, bool transpose_b, BlockView out);

}  // namespace coons::block_product_detail
