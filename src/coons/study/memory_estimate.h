// What a command is about to ask of memory, estimated before it is taken, and the limit it is
// held to: by default a fraction of the memory the system has available (MemAvailable of
// /proc/meminfo). The estimates are upper-bound sketches (documented per function), good to a
// factor of a few: their job is to refuse a 40000×40000 net or 10⁵×10⁵ samples with a clear
// message instead of std::bad_alloc.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "solvers/registry.h"

namespace coons {

//! MemAvailable of /proc/meminfo in bytes, or nullopt where it cannot be read.
std::optional<double> available_memory_bytes();

//! The default limit: half of the available memory (8 GiB where that is unknown).
double default_memory_limit();

//! "1000000", "512MB", "2GB", "1.5GiB", "64k": bytes; nullopt for anything else or below one byte.
std::optional<double> parse_memory_size(const std::string& text);

//! "1.2 GB"-style text for messages.
std::string format_bytes(double bytes);

//! Nonzeros a row of the mask system: the 3×3 masks and the 5×5 stencils (the C1 family).
constexpr int kMask3Nonzeros = 9;
constexpr int kStencil5Nonzeros = 25;

//! Solving the mask system of an (m+1)×(n+1) net with `solver` and keeping the net: the net,
//! frame and right-hand sides (≈ 10 copies of 3 doubles a point) plus the backend's share
//! (structured: ≈ 8 grids; iterative: the matrix, `stencil_nonzeros` entries a row; direct: the
//! matrix and a fill of ≈ 8·log₂(N) entries a row for a 3×3 mask, in proportion to
//! `stencil_nonzeros` for a wider stencil).
double net_solve_bytes(int m, int n, const solvers::SolverInfo* solver, int stencil_nonzeros = kMask3Nonzeros);

//! The entries a banded Gram matrix G^k keeps (banded_gram.h): rows of 32 hold the columns of
//! their kept entries, ≤ 11·√k + 32 of them a row (≤ 1.2 times what k = 100…10⁴ keep), all
//! (k+1) of them below k ≈ 100.
double banded_gram_entries(int k);

//! The exact energies of a net (energies.h: net_metrics): the banded Gram matrices of degrees
//! m, m−1, m−2, m−3 and n, …, n−3, one coordinate's grid about 10 times over (the differences and
//! Gram products of the four orders a direction), and the net.
double net_metrics_bytes(int m, int n);

//! A k×k sampling of a surface with its normals and the text of an OBJ or JSON of it.
double samples_bytes(long long k);

//! The k×k samples of a target objective: per coordinate the Coons net's samples and S, S', S''
//! (spectral_evaluation.cpp), 12 grids, and the products that make them: 16 k² doubles.
double target_samples_bytes(long long k);

}  // namespace coons
