// Event-driven integration as in the paper (Pfeiffer-Glocker): smooth phases integrated by
// ARKODE's explicit Runge-Kutta method, in which the closed contacts are constraints whose
// forces come from the acceleration-level LCP (eq. 5-8: normal contacts, sticking contacts with
// planar Coulomb friction, sliding contacts with their friction folded into the normal column),
// with Baumgarte stabilisation of the constraint drift; events located by root finding on the
// gaps of open contacts (closing), on the sliding velocities of sliding contacts (slip to
// stick) and on the friction reserve mu_s F_N - |F_T| of sticking contacts (stick to slip, the
// friction coefficient then drops to the kinetic one); at a closing event Newton's impact law for all contacts at the same time (the impact
// LCP, eq. 10-12), then the new contact configuration and a restart of the integrator. Contacts
// open, and sticking contacts start to slide, when the LCP lets them (checked after every step).
//
// Safeguards: a contact whose rebound speed after an impact is below `reboundThreshold` is
// closed (a second, plastic impact for it), so accumulating impacts (Zeno) end instead of
// tunnelling; an event rate above `maxEventsPerSecond`, measured over every batch of 100
// events, is reported as a runaway-event failure; an acceleration LCP without solution (ray termination, as for the
// Painleve rod with mu > 4/3) is reported as an error naming the contacts, never returned as a
// solution.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "nonsmooth/formulations.h"
#include "nonsmooth/method.h"
#include "nonsmooth/system.h"

namespace chaindrive::ns {

struct EventDrivenSettings {
  double rtol = 1e-7;
  double atolPosition = 1e-10;     // absolute tolerance on q
  double atolVelocity = 1e-7;      // absolute tolerance on v
  double maxStep = 0.0;            // 0: unlimited
  double reboundThreshold = 1e-4;  // [m/s] post-impact separation speed that closes the contact
  double stickSpeed = 1e-6;        // [m/s] a sticking contact slides beyond this tangential speed
  double gapTolerance = 1e-10;     // [m] closed contacts open beyond this gap
  double stabilization = 1e3;      // [1/s] Baumgarte rate of the constraint drift correction
  double maxEventsPerSecond = 2e5;
  int maxPivots = -1;
  std::string recordLcpDirectory;  // write the first recordLcpCount LCPs there (Siconos format)
  int recordLcpCount = 0;
  std::string erkTable = "ARKODE_DORMAND_PRINCE_7_4_5";
};

class EventDriven : public NonsmoothMethod {
 public:
  EventDriven(NonsmoothSystem& sys, const EventDrivenSettings& s);
  ~EventDriven() override;
  EventDriven(const EventDriven&) = delete;
  EventDriven& operator=(const EventDriven&) = delete;

  /// Starts at (t, q, v): classifies the contacts (closed where the gap is within tolerance and
  /// not separating; an impact first if some are approaching).
  void reset(double t, const double* q, const double* v) override;
  void advance(double tout) override;

  // for the C callbacks
  int rhs(double t, const double* y, double* ydot) noexcept;
  int roots(double t, const double* y, double* g) noexcept;

 private:
  enum class Mode { Stick, Slide };
  struct Closed {
    long long id;
    Mode mode;
    double sign;  // sliding direction (sign of gdot_T)
  };
  const Closed* findClosed(long long id) const;
  /// The acceleration LCP at (t, q, v); fills acc_ (and forces_ if `record`). False on failure.
  bool accelerations(double t, const double* q, const double* v, bool record);
  void impact(double t);                 // impact at the current state, then classification
  // the steps of impact(), in order
  void collectImpactRows();              // Newton's law rows of the contacts at the surface
  bool anyApproaching() const;
  void applyNewtonImpact(double t);      // the impact LCP and its impulses
  bool reboundsSlowly(double uN) const;
  void closeSlowRebounds(double t);      // a plastic impact for rebounds below the threshold
  void collectPlasticImpactRows();
  void applyPlasticImpact(double t);
  void classifyContacts();               // the closed contacts and their modes
  bool reclassify(double t);             // after a step; true if the configuration changed
  // the steps of advance(), in order
  int takeStep(double tout);             // one integrator step; returns the solver's flag
  [[noreturn]] void throwStepFailure(int flag);
  void handleRoots();                    // the events at a root: mode changes, impact
  void stickWhereSlidingStopped();
  void slideWhereFrictionSaturated();
  void countEvent();
  void checkEventRate();                 // throws on runaway events
  void restartIntegrator();
  void setupRoots();
  double kineticEnergy(const double* v) const;

  NonsmoothSystem& sys_;
  EventDrivenSettings settings_;
  const std::vector<double>& minv_;
  int n_;
  std::vector<double> h_, afree_, acc_, presc_, prescAcc_;
  std::vector<Closed> closed_;  // sorted by id
  std::vector<long long> sliding_;   // ids with a slip-to-stick root, in root order
  std::vector<long long> sticking_;  // ids with a stick-to-slip root, after the sliding ones
  ConstraintSet cs_;
  ConstraintSolver solver_;
  std::vector<ContactRow> rows_;
  std::vector<const Bilateral*> bil_;
  std::vector<double> bB_;
  // impact(): the velocities before it, the slow rebounds' closing rows and the plastic impact's
  // problem (its open contacts, its equality rows and their offsets)
  std::vector<double> vBefore_;
  std::vector<Bilateral> closing_;
  std::vector<ContactRow> others_;
  std::vector<const Bilateral*> eq_;
  std::vector<double> beq_;
  std::vector<int> rootInfo_;  // advance(): which root functions crossed zero
  double eventWindowStart_ = 0.0;
  long long eventWindowCount_ = 0;
  Failure lastFailure_;  // of the last failed right-hand side (its constraint problem)
  std::string solverMessage_;
  struct Sundials;
  std::unique_ptr<Sundials> sun_;
};

}  // namespace chaindrive::ns
