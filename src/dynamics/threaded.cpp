#include "dynamics/threaded.h"

#include <algorithm>
#include <cmath>

#include "dynamics/body_forces.h"
#include "dynamics/contact_kinematics.h"
#include "dynamics/contact_lanes.h"
#include "dynamics/dynamics.h"
#include "dynamics/link_loops.h"

namespace chaindrive {

namespace {

// The larger of two squared openings, NaN where either is.
double largerOf(double a, double b) { return a != a || b != b ? std::nan("") : std::max(a, b); }

LinkMoves mergedMoves(const Data& d) {
  LinkMoves all;
  for (const ThreadPart& part : d.threads.parts) {
    all.center2 = std::max(all.center2, part.moves.center2);
    all.axis2 = std::max(all.axis2, part.moves.axis2);
    all.nan |= part.moves.nan;
  }
  return all;
}

// What the threads of one evaluation share.
struct Evaluation {
  const Model& m;
  Data& d;
  const double* y;
  double* ydot;
  double reachLink;
};

// Thread t's share of the links' stages: kinematics, joints, contacts, weight and derivatives.
void linkStages(Evaluation& e, int t) noexcept {
  const Model& m = e.m;
  Data& d = e.d;
  ThreadPart& part = d.threads.parts[t];
  StagePool& pool = *d.threads.pool;
  part.moves = {};
  for (const LinkRange& r : part.ranges) {
    linkKinematicsRange(m, d, e.y, r);
    linkMovesRange(d, r, part.moves);
  }
  pool.barrier(t);
  part.jointOpening2 = 0.0;
  for (const LinkRange& r : part.ranges) part.jointOpening2 = largerOf(part.jointOpening2, jointForcesRange(m, d, r));
  const bool keep = windowsKept(m, d, 0.0, mergedMoves(d));  // (the same on every thread)
  pool.barrier(t);
  if (!keep) {
    if (t == 0) scanSearchWindows(m, d, 0.0);
    pool.barrier(t);
  }
  for (const LinkRange& r : part.ranges) jointGenRange(m, d, r);
  shareContacts(m, d, e.reachLink, part);
  for (const LinkRange& r : part.ranges) {
    addLinkWeight(m, d, r);
    linkDerivatives(m, d, e.y, e.ydot, r);
  }
}

}  // namespace

bool splitsEvaluations(const Model& m, const Data& d) {
  return !d.listContacts && d.compliantContacts && d.jointForces && m.pulleys.empty();
}

bool evaluatesOnThreads(const Model& m, const Data& d) { return d.threads.pool && splitsEvaluations(m, d); }

// generalizedForces' and forwardCompliant's stages in their order: the serial ones on this
// thread, the links' on all, then the sums across links here.
void forwardCompliantOnThreads(const Model& m, Data& d, const InputSignal& in, double t, const double* y,
                               double* ydot) {
  ++d.rhsEvaluations;
  in.evaluate(t, d.inputs);
  rotorKinematics(m, d, y);
  std::fill(d.gen.begin() + m.rotorGen(0), d.gen.end(), 0.0);
  Evaluation e{m, d, y, ydot, placeGuides(m, d, 0.0)};
  auto stages = [&e](int thread) { linkStages(e, thread); };
  d.threads.pool->run(stages);
  double pIn = 0.0, pDiss = 0.0;
  pDiss += jointPowerSum(m, d);
  d.jointOpening2 = 0.0;
  for (const ThreadPart& part : d.threads.parts) d.jointOpening2 = largerOf(d.jointOpening2, part.jointOpening2);
  pDiss += sumSharedContacts(m, d);
  rotorStage(m, d, y, pIn, pDiss);
  otherDerivatives(m, d, y, ydot);
}

void jointDampingOnThreads(const Model& m, Data& d, double a, double* accel) {
  StagePool& pool = *d.threads.pool;
  auto passes = [&](int thread) {
    const std::vector<LinkRange>& ranges = d.threads.parts[thread].ranges;
    for (const LinkRange& r : ranges) dampingCopyRange(m, d, accel, r);
    pool.barrier(thread);
    for (const LinkRange& r : ranges) dampingForceRange(m, d, r);
    pool.barrier(thread);
    for (const LinkRange& r : ranges) dampingSweepRange(m, d, a, accel, r);
  };
  pool.run(passes);
}

}  // namespace chaindrive
