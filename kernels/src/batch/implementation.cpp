// The implementation table and the once-per-process choice (simdjson's `implementation` model):
// the kernels are chosen per process, never per point.
#include "batch/targets.hpp"  // first: the same target set as the kernels
#include <hwy/targets.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "batch/kernels.hpp"
#include "bezinv/kernels/batch.hpp"
#include "bezinv/kernels/detail/batch_selection.hpp"

namespace bezinv::kernels {

namespace batch {

void size_out_of_range(const char* kernel, int n, int min_size, int max_size) {
  throw std::out_of_range(std::string("bezinv kernels: ") + kernel + " is compiled for n = " +
                          std::to_string(min_size) + ".." + std::to_string(max_size) + ", called with n = " +
                          std::to_string(n));
}

}  // namespace batch

namespace {

struct Candidate {
  std::string_view name;
  std::int64_t target;  // Highway target bit
};
// Scalar first, best last.
constexpr std::array<Candidate, 3> kCandidates{{{"scalar", HWY_BASELINE_SCALAR}, {"avx2", HWY_AVX2}, {"avx512", HWY_AVX3}}};

struct Table {
  std::array<Implementation, kCandidates.size()> storage{};
  std::array<const Implementation*, kCandidates.size()> available{};
  std::size_t count = 0;

  Table() {
    const std::int64_t supported = hwy::SupportedTargets();
    for (std::size_t i = 0; i < kCandidates.size(); ++i) {
      const auto svd = batch::symmetric_svd_kernel(kCandidates[i].target);
      const auto null = batch::null_vector_kernel(kCandidates[i].target);
      const auto null_iterations = batch::null_vector_iterations_kernel(kCandidates[i].target);
      const auto null_seed = batch::null_vector_seed_kernel(kCandidates[i].target);
      const auto newton = batch::rational_newton_kernel(kCandidates[i].target);
      const auto sample = batch::nearest_sample_kernel(kCandidates[i].target);
      const auto nearest = batch::nearest_newton_kernel(kCandidates[i].target);
      const auto slope = batch::rational_slope_kernel(kCandidates[i].target);
      const auto parameter = batch::bernstein_parameter_kernel(kCandidates[i].target);
      const auto bezout = batch::bezout_matrix_kernel(kCandidates[i].target);
      const auto bezout_seed = batch::bezout_null_vector_seed_kernel(kCandidates[i].target);
      const auto space_check = batch::space_check_kernel(kCandidates[i].target);
      const auto formula = batch::formula_parameter_kernel(kCandidates[i].target);
      const auto formula_newton = batch::formula_newton_kernel(kCandidates[i].target);
      if (svd == nullptr || null == nullptr || null_iterations == nullptr || null_seed == nullptr || newton == nullptr ||
          sample == nullptr || nearest == nullptr || slope == nullptr || parameter == nullptr || bezout == nullptr ||
          bezout_seed == nullptr || space_check == nullptr || formula == nullptr || formula_newton == nullptr ||
          (supported & kCandidates[i].target) == 0)
        continue;
      storage[count] =
          Implementation{kCandidates[i].name, svd,   null,      null_iterations, null_seed,   newton,      sample,
                         nearest,             slope, parameter, bezout,          bezout_seed, space_check, formula,
                         formula_newton};
      available[count] = &storage[count];
      ++count;
    }
  }
};

const Table& table() {
  static const Table instance;
  return instance;
}

}  // namespace

std::span<const Implementation* const> available_implementations() {
  return {table().available.data(), table().count};
}

namespace detail {

bool implementation_compiled(std::string_view name) {
  for (const Candidate& candidate : kCandidates)
    if (candidate.name == name)
      return batch::symmetric_svd_kernel(candidate.target) != nullptr &&
             batch::null_vector_kernel(candidate.target) != nullptr;
  return false;
}

const Implementation* implementation_named(std::string_view name) {
  for (const Implementation* implementation : available_implementations())
    if (implementation->name == name) return implementation;
  return nullptr;
}

const Implementation& best_implementation() { return *available_implementations().back(); }

const Implementation& select_implementation(const char* requested, std::string& warning) {
  warning.clear();
  if (requested == nullptr) return best_implementation();
  if (const Implementation* named = implementation_named(requested)) return *named;
  const Implementation& best = best_implementation();
  // Appended piece by piece: GCC 12 gives a false -Wrestrict on chained std::string operator+.
  warning = "bezinv: BEZINV_KERNEL=";
  warning += requested;
  warning += " is unknown or not supported by this CPU; using ";
  warning += best.name;
  return best;
}

}  // namespace detail

const Implementation& active_implementation() {
  // Reporting on stderr here is the one exception to "never print inside the library": the choice
  // is made once, from the environment, and a wrong BEZINV_KERNEL must not go unnoticed.
  static const Implementation& chosen = [] () -> const Implementation& {
    std::string warning;
    const Implementation& implementation = detail::select_implementation(std::getenv("BEZINV_KERNEL"), warning);
    if (!warning.empty()) std::fprintf(stderr, "%s\n", warning.c_str());
    return implementation;
  }();
  return chosen;
}

}  // namespace bezinv::kernels
