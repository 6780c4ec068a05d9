// Forces on the bodies other than joints and contacts: the tensioner on its guide, load
// torques on free sprockets, the drive of the prescribed sprocket, guide pivot friction and
// weight, and the weight of the links.
#pragma once

#include "dynamics/data.h"
#include "assembly/model.h"

namespace chaindrive {

struct TensionerResult {
  double force = 0.0;   // [N] plunger force on the guide (>= 0)
  double stroke = 0.0;  // [m] plunger extension relative to the nominal (drawn) pose
  double rate = 0.0;    // [m/s]
  double torque = 0.0;  // [N m] on the guide rotor (math sense)
  double power = 0.0;   // dissipated [W]
  double energy = 0.0;  // spring energy [J] (the compressed oil's: tensionerEnergy)
  double supplyPower = 0.0;    // [W] the oil supply's (hydraulic)
  double chamberPressure = 0.0;  // [Pa] gauge, the chamber's (hydraulic; cavitating: the vapour's)
  HydraulicFlows flows;        // [m3/s] (hydraulic)
};
TensionerResult tensionerForce(const TensionerModel& t, Vec2 pivot, double cosA, double sinA, double rate,
                               const ChamberState& chamber);
/// The plunger's extension [m] relative to the nominal (drawn) pose, at the guide's angle (cos, sin).
double tensionerStroke(const TensionerModel& t, Vec2 pivot, double cosA, double sinA);

/// A hydraulic chamber at its oil content [m3] with the guide at angle (cos, sin): sets
/// chamber.ratio, and chamber.pressure from the content's law unless the chamber is held.
void fillChamber(const TensionerModel& t, Vec2 pivot, double cosA, double sinA, double content,
                 ChamberState& chamber);
/// The oil content [m3] that fills the chamber at gauge pressure [Pa] with the guide at angle (cos, sin).
double chamberOilAt(const TensionerModel& t, Vec2 pivot, double cosA, double sinA, double pressure);
/// The content that fills the chamber at rest, at the supply's gauge pressure [Pa] less the check
/// valve's cracking pressure (chamberRestPressure), with the guide at `guideAngle` [rad]: a start state's.
double chamberOilAtRest(const Model& m, double guideAngle, double supplyPressure);
/// Holds a chamber at rest for a static solve: its pressure chamberRestPressure at the supply's
/// gauge pressure [Pa], whatever its content.
void holdChamberAtRest(const TensionerModel& t, double supplyPressure, ChamberState& chamber);
/// The content's rate [m3/s]: the valves' and the leak's flows at the filled chamber.
double chamberOilRate(const TensionerModel& t, const ChamberState& chamber, const HydraulicFlows& flows);

/// The tensioner's stored energy [J]: its spring's and a hydraulic chamber's compressed oil,
/// p^2 V / (2 K) (what the energy balance of a run counts; not evaluated with every force).
double tensionerEnergy(const TensionerModel& t, const TensionerResult& r);

/// What a hydraulic chamber adds to the potential of a static solve, where its pressure is held,
/// beyond tensionerEnergy: the work of its force at that pressure and of the end stops, less the
/// compressed oil's energy [J] (0 for the spring-damper law).
double heldChamberPotential(const TensionerModel& t, const TensionerResult& r);

/// The oil's viscosity of a model's hydraulic tensioner at its temperature (0 without one).
double tensionerOilViscosity(const TensionerModel& t);

/// Adds the body forces to d.gen, sets the tensioner outputs; returns {input power, dissipated power}.
void evaluateBodyForces(const Model& m, Data& d, double& powerInput, double& powerDissipated);
/// Its two parts: the links' weight (links of range r), and the rest (rotors, tensioner).
void addLinkWeight(const Model& m, Data& d, LinkRange r);
void evaluateRotorBodyForces(const Model& m, Data& d, double& powerInput, double& powerDissipated);

/// The body forces on the rotors alone, shared by the link and span models: guide pivot friction
/// and weight, the tensioner, load torques on free sprockets and the power of the prescribed
/// drive. Adds to rotorGen (one entry per rotor, math sense); cosA, sinA, rate per rotor.
void evaluateRotorForces(const Model& m, const InputValues& in, const double* cosA, const double* sinA,
                         const double* rate, const ChamberState& chamber, double* rotorGen, TensionerResult& tensioner,
                         double& powerInput, double& powerDissipated);

/// Potential energy of gravity (links and guide weights) and the tensioner spring.
double bodyPotentialEnergy(const Model& m, const Data& d, double& gravityEnergy);

}  // namespace chaindrive
