// Compile-time guard of the one Eigen memory ABI every coons build shares with Debian's static
// libceres.a (see the top-level CMakeLists.txt): malloc-based allocation, 16-byte alignment.
#include <Eigen/Core>

static_assert(EIGEN_MALLOC_ALREADY_ALIGNED == 1,
              "coons: every build uses EIGEN_MALLOC_ALREADY_ALIGNED=1, as Ceres's compiled Eigen code does");
static_assert(EIGEN_DEFAULT_ALIGN_BYTES == 16,
              "coons: flags that change Eigen's alignment (-march=native, -mavx...) break the ABI shared with libceres.a");
