#pragma once
// How active_implementation() picks a kernel, exposed for tests (not part of the engine's API).
#include <string>
#include <string_view>

#include "bezinv/kernels/batch.hpp"

namespace bezinv::kernels::detail {

// The implementation called `name` if this build has it and this CPU runs it, else nullptr.
const Implementation* implementation_named(std::string_view name);

// Whether this build compiled the kernels of the implementation called `name`, whether or not this
// CPU runs them (a tree built with BEZINV_KERNEL_TARGETS=native has scalar and the CPU's best only).
bool implementation_compiled(std::string_view name);

// The best available implementation.
const Implementation& best_implementation();

// What BEZINV_KERNEL=`requested` selects (nullptr: variable unset -> best). An unknown or
// unsupported name selects the best and sets `warning` to the one line to report.
const Implementation& select_implementation(const char* requested, std::string& warning);

}  // namespace bezinv::kernels::detail
