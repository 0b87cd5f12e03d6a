#include "registry.h"

#include "coons/config.h"
#include "eigen_direct.h"
#include "eigen_iterative.h"
#include "mask_iterations.h"
#include "multigrid_solvers.h"
#include "separable_banded_solver.h"
#if COONS_HAVE_SUITESPARSE
#include "suitesparse_direct.h"
#endif
#if COONS_HAVE_FFTW
#include "fast5_solver.h"
#include "pcg_fast.h"
#include "structured_solvers.h"
#endif
#if COONS_HAVE_HYPRE
#include "hypre_solvers.h"
#endif

namespace coons::solvers {

const char* to_string(SolverFamily family) {
  switch (family) {
    case SolverFamily::kDirect:
      return "direct";
    case SolverFamily::kIterative:
      return "iterative";
    case SolverFamily::kStructured:
      return "structured";
  }
  return "direct";
}

namespace {

using Factory = std::unique_ptr<LinearSolver> (*)(const SolverOptions&);

struct Entry {
  SolverInfo info;
  Factory make;
};

const std::vector<Entry>& entries() {
  static const std::vector<Entry> list = {
    {{"eigen-ldlt", SolverFamily::kDirect, true, true, false, "Eigen SimplicialLDLT, AMD ordering"}, make_eigen_ldlt},
    {{"eigen-llt", SolverFamily::kDirect, true, true, false, "Eigen SimplicialLLT, AMD ordering"}, make_eigen_llt},
    {{"eigen-lu", SolverFamily::kDirect, true, false, false,
      "Eigen SparseLU, COLAMD ordering (indefinite systems too)"},
     make_eigen_lu},
#if COONS_HAVE_SUITESPARSE
    {{"cholmod", SolverFamily::kDirect, true, true, false, "CHOLMOD supernodal LL^T, AMD ordering"},
     make_cholmod_supernodal},
    {{"cholmod-simplicial", SolverFamily::kDirect, true, true, false, "CHOLMOD simplicial LDL^T, AMD ordering"},
     make_cholmod_simplicial},
    {{"umfpack", SolverFamily::kDirect, true, false, false, "UMFPACK multifrontal LU (indefinite systems too)"},
     make_umfpack},
#endif
    {{"cg", SolverFamily::kIterative, true, true, false, "conjugate gradients, no preconditioner"}, make_cg},
    {{"cg-jacobi", SolverFamily::kIterative, true, true, false, "conjugate gradients, diagonal preconditioner"},
     make_cg_jacobi},
    {{"cg-ic", SolverFamily::kIterative, true, true, false, "conjugate gradients, incomplete Cholesky"}, make_cg_ic},
    {{"bicgstab", SolverFamily::kIterative, true, false, false, "BiCGSTAB with incomplete LU (ILUT)"}, make_bicgstab},
    {{"jacobi", SolverFamily::kIterative, false, false, false, "the Jacobi mask iteration (diverges for alpha < 0)"},
     make_jacobi},
    {{"gauss-seidel", SolverFamily::kIterative, false, false, false, "the Gauss-Seidel / SOR mask iteration (--omega)"},
     make_gauss_seidel},
#if COONS_HAVE_FFTW
    {{"dst", SolverFamily::kStructured, false, false, true,
      "2-D discrete sine transform (DST-I on a real FFT), exact for any alpha on rectangular grids"},
     make_dst_solver},
    {{"fast", SolverFamily::kStructured, false, false, true,
      "sine transform along j + tridiagonal solves along i; Kronecker path for alpha = -1/4; exact for any alpha"},
     make_fast_solver},
    {{"fast5", SolverFamily::kStructured, false, false, true,
      "5x5 a*C + b*T stencils (c1-coons, c1-family, biharmonic) on a full rectangle: sine transform along j, "
      "banded solves along i, capacitance CG on the first and last column; exact"},
     make_fast5_solver},
#endif
    {{"separable-banded", SolverFamily::kStructured, false, false, true,
      "separable stencils u(a) v(b) (c1-coons, alpha = -1/4) on a full rectangle: two batches of banded LDL^T "
      "solves; exact"},
     make_separable_banded},
    {{"mg", SolverFamily::kIterative, false, false, true,
      "geometric multigrid V-cycles, alternating line Gauss-Seidel, Galerkin coarse grids (3x3/5x5 stencils, free "
      "sets)"},
     make_mg},
    {{"mg-cg", SolverFamily::kIterative, false, true, true,
      "conjugate gradients preconditioned by one symmetric multigrid V-cycle"},
     make_mg_cg},
    {{"gmres", SolverFamily::kIterative, false, false, true,
      "restarted GMRES(50), multigrid-preconditioned on a grid stencil, else ILUT (nonsymmetric systems)"},
     make_gmres},
#if COONS_HAVE_FFTW
    {{"pcg-fast", SolverFamily::kIterative, false, true, false,
      "conjugate gradients preconditioned by the exact structured solve of the bounding rectangle (free sets with "
      "holes, L-shapes, fixed curves)"},
     make_pcg_fast_solver},
#endif
#if COONS_HAVE_HYPRE
    {{"hypre-amg", SolverFamily::kIterative, true, false, false,
      "hypre BoomerAMG preconditioning PCG (symmetric) or GMRES (otherwise), on the matrix; MPI-distributed"},
     make_hypre_amg},
    {{"hypre-pfmg", SolverFamily::kIterative, false, true, false,
      "hypre PFMG V-cycle preconditioning PCG on the grid stencil (Struct interface); MPI-distributed"},
     make_hypre_pfmg},
    {{"hypre-smg", SolverFamily::kIterative, false, true, false,
      "hypre SMG V-cycle preconditioning PCG on the grid stencil (Struct interface); MPI-distributed"},
     make_hypre_smg},
#endif
  };
  return list;
}

}  // namespace

const std::vector<SolverInfo>& available_solvers() {
  static const std::vector<SolverInfo> infos = [] {
    std::vector<SolverInfo> out;
    for (const auto& e : entries()) out.push_back(e.info);
    return out;
  }();
  return infos;
}

const SolverInfo* find_solver(std::string_view name) {
  for (const auto& info : available_solvers())
    if (info.name == name) return &info;
  return nullptr;
}

std::string choose_auto_solver(const GridStencil& stencil) {
#if COONS_HAVE_FFTW
  (void)stencil;
  return "fast";  // exact for every non-singular stencil, and the fastest
#else
  const auto [lo, hi] = stencil_eigenvalue_range(stencil);
  const bool definite = lo > 0 && hi > 0;
  return definite ? "eigen-ldlt" : "eigen-lu";
#endif
}

bool accepts_matrix(const SolverInfo& info) {
  if (info.needs_matrix) return true;
  Eigen::SparseMatrix<double> one(1, 1);
  one.insert(0, 0) = 1.0;
  LinearOperator op;
  op.matrix = &one;
  const auto solver = make_solver(info.name);
  return solver && solver->analyze(op) != SolveStatus::kNotApplicable;
}

bool uses_threads(std::string_view name) {
  const SolverInfo* info = find_solver(name);
  return info != nullptr && info->uses_threads;
}

const SolverInfo& default_matrix_solver(bool definite) {
  const SolverInfo* pick = definite ? find_solver("cholmod") : nullptr;
  if (!pick) pick = find_solver(definite ? "eigen-ldlt" : "eigen-lu");
  return *pick;  // (the Eigen backends are always built)
}

std::unique_ptr<LinearSolver> make_solver(std::string_view name, const SolverOptions& options) {
  for (const auto& e : entries())
    if (e.info.name == name) return e.make(options);
  return nullptr;
}

}  // namespace coons::solvers
