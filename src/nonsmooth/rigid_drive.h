// The chain drive with rigid contacts (and optionally ideal joints) as a NonsmoothSystem for the
// complementarity methods, and the adapter that lets the Simulation drive those methods through
// the Integrator interface. The contact kinematics are the same as for the compliant contacts
// (contact_kinematics.h): gaps, normals, lever arms and the W columns; only the laws differ.
// On a CVT the pins' normal force stays the compliant one of their axial stiffness (the paper's
// elastic bolt) and their friction, radial and circumferential, becomes the constraint; or, with
// rigid pins (the axial stiffness's limit), a pin is a unilateral contact on its pulley's running
// circle, closing with Newton's impact law (restitution of the CVT's contact), its friction
// circumferential with the wedge's coefficient mu / sin(beta): a pressed rigid pin cannot slide
// radially (moving in would compress it, moving out opens the contact), so the radial friction
// has no sliding to oppose and is not separable from the normal force.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "dynamics/data.h"
#include "dynamics/health.h"
#include "integrators/ode_system.h"
#include "assembly/model.h"
#include "nonsmooth/event_driven.h"
#include "nonsmooth/moreau_jean.h"
#include "nonsmooth/system.h"

namespace chaindrive {

class RigidContactDrive : public ns::NonsmoothSystem {
 public:
  RigidContactDrive(std::shared_ptr<const Model> m, const InputSignal& in, bool idealJoints, const HealthLimits& health,
                    bool rigidPins = false);
  int size() const override { return n_; }
  const std::vector<double>& inverseMass() const override { return minv_; }
  void prescribed(double t, double* v, double* a) const override;
  void forces(double t, const double* q, const double* v, double* h) override;
  void constraints(double t, const double* q, const double* v, double margin, bool accelerations,
                   ns::ConstraintSet& out) override;
  double dissipatedPower(double t, const double* q, const double* v) override;
  double inputPower(double t, const double* q, const double* v) override;
  bool healthy(double t, const double* q, const double* v, Failure& why) override;
  void advanceSmoothStates(double h) override;

  /// State vector (compliant layout, y) <-> (q, v).
  void unpack(const double* y, double* q, double* v) const;
  void pack(const double* q, const double* v, double* y) const;
  /// The smooth states beside q and v (a hydraulic tensioner's chamber oil content) from y, into y.
  void setSmoothStates(const double* y);
  void smoothStates(double* y) const;
  /// The contact points of the last constraints() call with the given forces (outputs).
  void contactPoints(const std::vector<ns::ContactForce>& f, std::vector<ContactPoint>& out) const;
  bool idealJoints() const { return ideal_; }
  const Model& model() const { return *model_; }

 private:
  void evaluate(double t, const double* q, const double* v);  // kinematics and smooth forces into d_
  ns::Contact pinContact(ContactPoint& c, int k);
  ns::Contact rigidContact(const ContactPoint& c, int k, bool accelerations) const;
  void idealJointConstraints(bool accelerations, ns::ConstraintSet& out) const;
  void contactsAlongTheMotion(int sgn, std::vector<ContactPoint>& dst);
  static constexpr double kProbeStep = 1e-7;  // the probes' time step along the motion (wbar)
  std::shared_ptr<const Model> model_;
  const InputSignal& in_;
  bool ideal_;
  bool rigidPins_;
  HealthLimits health_;
  int n_;
  std::vector<double> minv_, y_, yp_;
  Data d_, dp_;                          // evaluation and perturbed evaluation (wbar)
  std::vector<ContactPoint> last_;       // contact points of the last constraints() call
  std::vector<ContactPoint> probes_[2];  // last_ moved forward and backward along the motion (wbar)
  mutable InputValues inputs_;
};

/// Rigid-contact method (event-driven or time-stepping) behind the Integrator interface.
class RigidIntegrator : public Integrator {
 public:
  /// method: time stepping or event driven.
  RigidIntegrator(std::shared_ptr<RigidContactDrive> sys, ContactMethod method, const IntegratorSettings& s);
  void reset(double t0, const double* y0) override;
  void advance(double tout, double* y) override;
  IntegratorStats stats() const override;
  std::string name() const override { return choiceName(method_); }
  double fixedStep() const override { return fixedStep_; }
  const ns::NsStats& contactStats() const;
  /// Contact points with the forces of the last step (mean force over it for time stepping).
  void contactPoints(std::vector<ContactPoint>& out) const;
  /// Ideal joints: the constraint forces (fx, fy per joint); empty for journal bearings.
  const std::vector<double>& jointForces() const;

 private:
  std::shared_ptr<RigidContactDrive> sys_;
  ContactMethod method_;
  std::unique_ptr<ns::NonsmoothMethod> ns_;
  double fixedStep_ = 0.0;  // time stepping: its step; event driven: 0 (adaptive)
  std::vector<double> q_, v_;
};

}  // namespace chaindrive
