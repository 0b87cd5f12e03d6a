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

//! "1000000", "512MB", "2GB", "1.5GiB", "64k": bytes; nullopt for anything else or ≤ 0.
std::optional<double> parse_memory_size(const std::string& text);

//! "1.2 GB"-style text for messages.
std::string format_bytes(double bytes);

//! Solving the mask system of an (m+1)×(n+1) net with `solver` and keeping the net: the net,
//! frame and right-hand sides (≈ 10 copies of 3 doubles a point) plus the backend's share
//! (structured: ≈ 8 grids; iterative: the matrix, 9 entries a row; direct: the matrix and a
//! fill of ≈ 8·log₂(N) entries a row).
double net_solve_bytes(int m, int n, const solvers::SolverInfo* solver);

//! The exact energies of a net: Gram matrices and derivative nets, (m+1)² + (n+1)² doubles a few
//! times over, plus the net.
double net_metrics_bytes(int m, int n);

//! A k×k sampling of a surface with its normals and the text of an OBJ or JSON of it.
double samples_bytes(long long k);

}  // namespace coons
