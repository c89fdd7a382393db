#pragma once
// Reading parameters back from null vectors of a resultant matrix.
// If z = alpha * (beta_0^{(N)}(t), ..., beta_N^{(N)}(t)) with N = size-1, consecutive components
// satisfy  z_i / z_{i-1} = (N+1-i) t / (i (1-t)),  hence (Marco & Martinez Sect. 3)
//     t = i z_i / (i z_i + (N+1-i) z_{i-1}).
#include <span>

namespace bezinv {

// The paper's read-out: the component of largest magnitude, and of its two neighbours the larger
// one (the largest components are the least sensitive to perturbations, Demmel et al. 2008).
// z.size() >= 2. Returns NaN when the two components are both zero.
double parameter_from_null_vector(std::span<const double> z);

// Two-dimensional null space spanned by u and v (same size N+1 >= 3): find the parameters t with
// beta^{(N)}(t) in span{u, v}. Each column c = a u + b v must satisfy, for i = 1..N,
//     i (1-t) c_i - (N+1-i) t c_{i-1} = 0,
// a rectangular pencil A c = t (A + D) c with A_i = i c_i and D_i = (N+1-i) c_{i-1}. It is squared up
// by least squares (multiplying by (A + D)^T) into a 2x2 generalized eigenproblem. Writes the real
// finite roots to t (at most 2) and returns how many there are. A root at infinity (a degree drop)
// or a complex pair is not returned.
int parameters_from_null_space(std::span<const double> u, std::span<const double> v, double t[2]);

// The same for a null space of any dimension k (2 <= k <= N): the k vectors of size N+1 lie one
// after the other in `basis` (vector j from basis[j (N+1)]). A point with k parameters over C (an
// improperly parametrized curve: every point of Q(phi(t)) has deg phi of them; a straight line
// traced at degree n has n) has the Bernstein vectors of all k in the null space of B, so the
// pencil above, k x k after the least-squares step, has them for its eigenvalues. Solved by the
// QZ algorithm, so that a root at infinity (the pencil's E singular) is a zero beta, skipped.
// Writes the real finite roots, in increasing order, to t (room for k) and returns how many.
// Complex roots are returned by their real part when their imaginary part is within
// kComplexRootSlack of it (a real double root split by rounding); every root is only a candidate,
// which the caller verifies by its distance to the point.
int parameters_from_null_space(std::span<const double> basis, int k, std::span<double> t);

}  // namespace bezinv
