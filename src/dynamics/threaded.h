// An evaluation of the link model on several threads (solver.threads): the per-link stages of
// forwardCompliant and of the joints' damping sweep split by links (Data::useThreads: a
// contiguous part of the chain per thread), a barrier wherever a stage reads its
// neighbours' results, and every sum across links formed afterwards on the calling thread in the
// order of the serial code, so that every number of threads gives the bits of one. For the
// evaluations that list no contacts (the fixed-step methods' derivatives) of a drive without
// pulleys, with the compliant contacts and the journal bearings.
#pragma once

#include "assembly/model.h"
#include "dynamics/data.h"

namespace chaindrive {

/// Whether d's evaluations are of the kind above (so could run on threads) ...
bool splitsEvaluations(const Model& m, const Data& d);
/// ... and run on them: a pool of more than one thread too.
bool evaluatesOnThreads(const Model& m, const Data& d);

/// forwardCompliant on the threads.
void forwardCompliantOnThreads(const Model& m, Data& d, const InputSignal& in, double t, const double* y,
                               double* ydot);

/// jointDampingOffDiagonalLoop on the threads.
void jointDampingOnThreads(const Model& m, Data& d, double a, double* accel);

}  // namespace chaindrive
