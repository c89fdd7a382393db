#pragma once
// The per-instruction-set entry points of the batch kernels, looked up by Highway target bit
// (HWY_EMU128, HWY_AVX2, HWY_AVX3). Only implementation.cpp needs this.
#include <cstddef>
#include <cstdint>

#include "bezinv/kernels/batch.hpp"

namespace bezinv::kernels::batch {

using SymmetricSvdKernel = void (*)(int n, std::size_t count, std::size_t stride, const double* B, double* sigma,
                                    double* V);
using NullVectorKernel = void (*)(int n, std::size_t count, std::size_t stride, const double* B, double* z,
                                  double* defect, double* estimate, double* second);
using NullVectorIterationsKernel = void (*)(int n, int iterations, std::size_t count, std::size_t stride,
                                            const double* B, double* z, double* defect, double* estimate,
                                            double* second);
using NullVectorSeedKernel = void (*)(int n, std::size_t count, std::size_t stride, const double* B, double* z,
                                      double* defect, double* residual, double settled_defect);
using RationalNewtonKernel = std::size_t (*)(const RationalCurve& curve, const NewtonSettings& settings,
                                             std::size_t count, const double* u, const double* v, double* t,
                                             double* distance);
using NearestSampleKernel = void (*)(const double* samples, int last, int stride, std::size_t count,
                                     const double* u, const double* v, double* t);
using NearestNewtonKernel = void (*)(const RationalCurve& curve, const NearestNewtonSettings& settings,
                                     std::size_t count, const double* u, const double* v, double* t,
                                     double* distance);
using RationalSlopeKernel = void (*)(const RationalCurve& curve, std::size_t count, const double* t, double* x,
                                     double* y, double* dx, double* dy);
using BernsteinParameterKernel = void (*)(int n, std::size_t count, std::size_t stride, const double* z, double* t);
using BezoutMatrixKernel = void (*)(int n, std::size_t count, std::size_t stride, const double* B0, const double* Bx,
                                    const double* By, const double* Bxy, const double* u, const double* v, double* B,
                                    double* poison);
using BezoutNullVectorSeedKernel = void (*)(int n, std::size_t count, std::size_t stride, const double* B0,
                                            const double* Bx, const double* By, const double* Bxy, const double* u,
                                            const double* v, double* z, double* defect, double* residual,
                                            double* poison, double settled_defect);
using SpaceCheckKernel = void (*)(const SpaceCurve& curve, std::size_t count, const double* t, const double* x,
                                  const double* y, const double* z, double* distance);
using FormulaParameterKernel = void (*)(const PlaneFormula& formula, std::size_t count, const double* u,
                                        const double* v, double* t);
using FormulaNewtonKernel = std::size_t (*)(const PlaneFormula& formula, const RationalCurve& curve,
                                            const NewtonSettings& settings, const PointFrame& frame,
                                            const PieceCertificate& certificate, double tolerance, std::size_t count,
                                            const double* xy, double* t, double* distance,
                                            const FormulaStart* start, const FormulaLanes* lanes);

// nullptr when this build did not compile `target`.
SymmetricSvdKernel symmetric_svd_kernel(std::int64_t target);
NullVectorKernel null_vector_kernel(std::int64_t target);
NullVectorIterationsKernel null_vector_iterations_kernel(std::int64_t target);
NullVectorSeedKernel null_vector_seed_kernel(std::int64_t target);
RationalNewtonKernel rational_newton_kernel(std::int64_t target);
NearestSampleKernel nearest_sample_kernel(std::int64_t target);
NearestNewtonKernel nearest_newton_kernel(std::int64_t target);
RationalSlopeKernel rational_slope_kernel(std::int64_t target);
BernsteinParameterKernel bernstein_parameter_kernel(std::int64_t target);
BezoutMatrixKernel bezout_matrix_kernel(std::int64_t target);
BezoutNullVectorSeedKernel bezout_null_vector_seed_kernel(std::int64_t target);
SpaceCheckKernel space_check_kernel(std::int64_t target);
FormulaParameterKernel formula_parameter_kernel(std::int64_t target);
FormulaNewtonKernel formula_newton_kernel(std::int64_t target);

}  // namespace bezinv::kernels::batch
