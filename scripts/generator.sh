# Sourced by the build scripts. generator_args DIR: "-G Ninja" for a new build tree (Ninja keeps
# every core busy to the end of a build, where make leaves the largest kernels to one), nothing
# for a tree configured before (CMake refuses to change a tree's generator).
generator_args() { [ -f "$1/CMakeCache.txt" ] || echo "-G Ninja"; }
