// out = a·b or a·bᵀ for dense column-major blocks given by a pointer, their sizes and their column
// stride, by Eigen's GEMM compiled for the widest instruction set that both this build and this
// CPU have. The whole build keeps Eigen's SSE2 memory ABI, which it shares with Debian's static
// libceres.a (cmake/eigen_abi_check.cpp), so Eigen's products run 2-wide everywhere else; this
// kernel is compiled a second and a third time with -mavx2 -mfma and -mavx512f, each with Eigen's
// namespace renamed so that none of its template instances can stand in for the SSE2 ones
// (src/CMakeLists.txt; the CTest tests block_product_isa_objects_keep_their_symbols_* check it), and
// the set is chosen per call from what the CPU reports. Every block is multiplied alike on any
// thread, so results do not depend on the thread count; they do depend, in the last bits, on the set.
// Measured on 2026-11-29 (Xeon, 2 cores), 32 × 330 by 330 × 1001 blocks: 10 Gflop/s baseline,
// 22 with AVX2, 39 with AVX-512. Used by BandedGram (the exact energies of large nets).
#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

namespace coons {

//! A read-only column-major block: entry (i, j) at data[i + j·stride], stride ≥ rows.
struct ConstBlockView {
  const double* data = nullptr;
  std::ptrdiff_t rows = 0, cols = 0, stride = 0;
};

//! A writable column-major block.
struct BlockView {
  double* data = nullptr;
  std::ptrdiff_t rows = 0, cols = 0, stride = 0;
};

enum class InstructionSet { kBaseline, kAvx2, kAvx512 };

//! The sets built into this binary that this CPU runs, the baseline first and the widest last.
[[nodiscard]] std::vector<InstructionSet> available_instruction_sets();
//! The last of available_instruction_sets() (decided once per process).
[[nodiscard]] InstructionSet widest_instruction_set();
[[nodiscard]] std::string_view instruction_set_name(InstructionSet set);

//! out = a·b (transpose_b false: a.cols == b.rows) or a·bᵀ (true: a.cols == b.cols); out must not
//! overlap a or b and has a.rows rows. A set this CPU does not run falls back to the baseline.
void block_product(ConstBlockView a, ConstBlockView b, bool transpose_b, BlockView out,
                   InstructionSet set = widest_instruction_set());

}  // namespace coons
