// Loops over arrays of doubles that the solver runs at every evaluation, in vector instructions:
// AVX2 where the CPU has it, SSE2 elsewhere (simd.h), each element the same operations as
// one at a time and without FMA, so the same bits on every x86-64 machine. Arrays must not overlap.
#pragma once

namespace chaindrive {

/// out[i] = factor x[i] for i < n.
void scaleInto(double* __restrict out, const double* __restrict x, double factor, int n);

/// y[i] += c for i < n.
void addConstant(double* __restrict y, double c, int n);

}  // namespace chaindrive
