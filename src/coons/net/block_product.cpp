#include "coons/net/block_product.h"

#include <array>
#include <cstddef>

#include "coons/net/block_product_kernel.h"

namespace coons {

namespace {

// What the CPU reports, asked once per process.
bool detect(InstructionSet set) {
#if defined(COONS_HAVE_BLOCK_PRODUCT_AVX2) || defined(COONS_HAVE_BLOCK_PRODUCT_AVX512)
  __builtin_cpu_init();  // needed if this runs before libgcc's own constructor
#endif
  switch (set) {
    case InstructionSet::kBaseline:
      return true;
    case InstructionSet::kAvx2:
#if defined(COONS_HAVE_BLOCK_PRODUCT_AVX2)
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
      return false;
#endif
    case InstructionSet::kAvx512:
#if defined(COONS_HAVE_BLOCK_PRODUCT_AVX512)
      return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("fma");
#else
      return false;
#endif
  }
  return false;
}

bool cpu_runs(InstructionSet set) {
  static const std::array<bool, 3> runs{detect(InstructionSet::kBaseline), detect(InstructionSet::kAvx2),
                                        detect(InstructionSet::kAvx512)};
  return runs[static_cast<std::size_t>(set)];
}

}  // namespace

std::vector<InstructionSet> available_instruction_sets() {
  std::vector<InstructionSet> sets;
  for (InstructionSet set : {InstructionSet::kBaseline, InstructionSet::kAvx2, InstructionSet::kAvx512})
    if (cpu_runs(set)) sets.push_back(set);
  return sets;
}

InstructionSet widest_instruction_set() {
  static const InstructionSet widest = available_instruction_sets().back();
  return widest;
}

std::string_view instruction_set_name(InstructionSet set) {
  switch (set) {
    case InstructionSet::kBaseline:
      return "baseline";
    case InstructionSet::kAvx2:
      return "avx2";
    case InstructionSet::kAvx512:
      return "avx512";
  }
  return "unknown";
}

void block_product(ConstBlockView a, ConstBlockView b, bool transpose_b, BlockView out, InstructionSet set) {
  if (!cpu_runs(set)) set = InstructionSet::kBaseline;
  switch (set) {
#if defined(COONS_HAVE_BLOCK_PRODUCT_AVX512)
    case InstructionSet::kAvx512:
      block_product_detail::multiply_avx512(a, b, transpose_b, out);
      return;
#endif
#if defined(COONS_HAVE_BLOCK_PRODUCT_AVX2)
    case InstructionSet::kAvx2:
      block_product_detail::multiply_avx2(a, b, transpose_b, out);
      return;
#endif
    default:
      block_product_detail::multiply_baseline(a, b, transpose_b, out);
  }
}

}  // namespace coons
