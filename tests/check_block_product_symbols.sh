#!/usr/bin/env bash
# check_block_product_symbols.sh SET OBJECT: the object of block_product_kernel.cpp compiled for
# SET (src/CMakeLists.txt) defines multiply_SET, and every weak or unique symbol it defines (the
# template instances a linker may merge with those of other objects) lies in its own renamed Eigen
# namespace coons_eigen_SET. A weak Eigen or standard-library instance compiled with AVX could
# otherwise be the copy the linker keeps for the whole program, and run on a CPU without AVX.
set -euo pipefail
set_name=$1 object=$2
symbols=$(nm -C --defined-only "$object")
if ! grep -q "coons::block_product_detail::multiply_${set_name}(" <<<"$symbols"; then
  echo "check_block_product_symbols: $object does not define multiply_${set_name}" >&2
  exit 1
fi
# weak (W, V), unique global (u); the personality routine's reference (DW.ref.*) is data, the same everywhere
stray=$(awk '$2 ~ /^[WVu]$/' <<<"$symbols" | grep -v "coons_eigen_${set_name}::" | grep -v ' DW\.ref\.' || true)
weak=$(awk '$2 ~ /^[WVu]$/' <<<"$symbols" | wc -l)
if [[ -n $stray ]]; then
  echo "check_block_product_symbols: $object defines weak symbols outside coons_eigen_${set_name}:" >&2
  echo "$stray" >&2
  exit 1
fi
echo "check_block_product_symbols: $set_name: $weak weak or unique symbols, all in coons_eigen_${set_name} (or DW.ref.*)"
