#pragma once
// Portable random numbers for the generators. std::uniform_real_distribution's output is
// implementation-defined (libstdc++ and libc++ differ), so a seed would name different data on
// different machines; these draw from the raw std::mt19937_64 stream, whose output the standard
// fixes, so a seed printed by a failing test reproduces the same curve everywhere.
#include <cstdint>
#include <random>

namespace bezinv::datasets {

// Uniform in [lo, hi): the top 53 bits of one draw as a fraction.
double uniform(std::mt19937_64& rng, double lo, double hi);

// Uniform integer in [lo, hi] (small ranges; the modulo bias is below 2^-50).
int uniform_int(std::mt19937_64& rng, int lo, int hi);

// exp(uniform(log lo, log hi)): for distances spanning decades.
double log_uniform(std::mt19937_64& rng, double lo, double hi);

}  // namespace bezinv::datasets
