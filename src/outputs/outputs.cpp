#include "outputs/outputs.h"

#include <cmath>

#include "dynamics/pin_sheave.h"
#include "dynamics/contact_compliant.h"
#include "dynamics/joint_forces.h"

namespace chaindrive {

double spanForce(const Model& m, const Data& d, const SpanProbe& probe) {
  if (!probe.present) return 0.0;
  const int n = m.chain.links;
  const double near = 2.0 * m.chain.pitch;
  for (int j = 0; j < n; ++j) {
    const int k = j + 1 == n ? 0 : j + 1;
    const Vec2 pj = d.links[j].front, pk = d.links[k].front;  // joints j and k
    const double aj = dot(pj - probe.point, probe.direction), ak = dot(pk - probe.point, probe.direction);
    if (!(aj <= 0.0 && ak > 0.0)) continue;
    if (std::fabs(cross(probe.direction, pj - probe.point)) > near) continue;
    const double w = -aj / (ak - aj);
    return (1.0 - w) * d.joints.tension[j] + w * d.joints.tension[k];
  }
  return std::nan("");
}

void finishRotorOutputs(const Model& m, const std::vector<double>& angle, const std::vector<double>& rate,
                        const ImpulseStates& impulse, const double* y, Outputs& out) {
  const std::vector<double>& sign = m.rotorOutputSign;
  const std::size_t nr = m.rotors.size();
  out.rotorAngle.resize(nr);
  out.rotorRate.resize(nr);
  out.rotorTorqueStepMean.resize(nr);
  // no time accumulated yet (the start, or a step just begun): the mean's limit, the torque itself
  const double span = y ? y[impulse.time] : 0.0;
  for (std::size_t r = 0; r < nr; ++r) {
    const RotorModel& ro = m.rotors[r];
    out.rotorAngle[r] = sign[r] * (angle[r] - (ro.isSprocket ? ro.initialAngle : 0.0));
    out.rotorRate[r] = sign[r] * rate[r];
    out.rotorTorque[r] *= sign[r];
    out.rotorTorqueStepMean[r] = !y ? std::nan("") : span > 0.0 ? sign[r] * y[impulse.first + r] / span : out.rotorTorque[r];
  }
  out.crankTorque = m.drivenRotor >= 0 ? out.rotorTorque[m.drivenRotor] : 0.0;
  out.crankTorqueStepMean = m.drivenRotor >= 0 ? out.rotorTorqueStepMean[m.drivenRotor] : 0.0;
}

namespace {

// Rigid contacts and ideal joints: the forces of the method's last step in place of a force law.
void carryRigidForces(const Model& m, const RigidForces& rigid, Data& d) {
  if (rigid.contacts) {
    d.nContacts = 0;
    for (const ContactPoint& c : *rigid.contacts) {
      if (d.nContacts >= static_cast<int>(d.contacts.size())) break;
      d.contacts[d.nContacts++] = c;
      addContactGen(m, c, d.gen.data());
      // (a CVT pin's compliant normal is not among the smooth forces evaluated here)
      if (c.kind == ContactPoint::Kind::PinSheave) d.powerDissipated += constrainedPinPower(m, c);
    }
  }
  // ideal joints: the constraint forces, their tension along the links' mean axis
  if (rigid.joints && static_cast<int>(rigid.joints->size()) == 2 * m.chain.links) {
    const int n = m.chain.links;
    for (int j = 0; j < n; ++j) {
      const Vec2 force{(*rigid.joints)[2 * j], (*rigid.joints)[2 * j + 1]};
      d.joints.setForce(j, force);
      d.joints.tension[j] = jointTension(d.links[j], d.links[(j + 1) % n], force);
      d.joints.deformation[j] = norm(d.links[j].front - d.links[(j + 1) % n].rear);
    }
  }
}

// The monitored link: the mean tension of its two joints, its position and its contact forces.
void monitoredLinkOutputs(const Model& m, const Data& d, int monitoredLink, Outputs& out) {
  const int n = m.chain.links;
  const int L = (monitoredLink >= 0 && monitoredLink < n) ? monitoredLink : m.monitoredLink;
  const LinkKin& lk = d.links[L];
  out.linkTension = 0.5 * (dot(d.joints.force(L), lk.e) + dot(d.joints.force((L + n - 1) % n), lk.e));
  out.linkPosition = lk.c;
  out.linkNormalForce = out.linkSprocketForce = out.linkGuideForce = 0.0;
  for (int i = 0; i < d.nContacts; ++i) {
    const ContactPoint& c = d.contacts[i];
    if (c.link != L) continue;
    out.linkNormalForce += c.fN;
    (c.kind == ContactPoint::Kind::RollerSprocket ? out.linkSprocketForce : out.linkGuideForce) += c.fN;
  }
}

}  // namespace

void computeOutputs(const Model& m, Data& d, const InputSignal& in, double t, const double* y, int monitoredLink,
                    Outputs& out, const RigidForces* rigid) {
  // the smooth forces at this state; rigid contacts and ideal joints carry the forces of the
  // method's last step instead of a force law
  d.compliantContacts = rigid == nullptr;
  d.jointForces = rigid == nullptr || rigid->joints == nullptr;
  const bool listing = d.listContacts;  // (the outputs read the contacts)
  d.listContacts = true;
  generalizedForces(m, d, in, t, y);
  d.listContacts = listing;
  if (d.jointForces) measureJoints(m, d);
  if (rigid) carryRigidForces(m, *rigid, d);
  // rotors: angles from their start, rates and the chain's torque on them, in the output sense
  const std::size_t nr = m.rotors.size();
  out.time = t;
  out.rotorTorque.assign(nr, 0.0);
  for (int i = 0; i < d.nContacts; ++i) {
    const ContactPoint& c = d.contacts[i];
    if (c.rotor < 0) continue;
    out.rotorTorque[c.rotor] -= cross(c.rRotor, contactForce(c));
  }
  finishRotorOutputs(m, d.rotorAngle, d.rotorRate, m.chainImpulse, rigid ? nullptr : y, out);
  // tensioner and span forces
  out.tensionerForce = d.tensionerForce;
  out.tensionerStroke = d.tensionerStroke;
  out.tensionerRate = d.tensionerRate;
  out.chamberPressure = d.chamberPressure;
  out.tensionerFlows = d.tensionerFlows;
  out.tightSpanForce = spanForce(m, d, m.tightSpan);
  out.slackSpanForce = spanForce(m, d, m.slackSpan);
  out.spanForce.resize(m.spanProbes.size());
  for (std::size_t r = 0; r < m.spanProbes.size(); ++r) out.spanForce[r] = spanForce(m, d, m.spanProbes[r]);
  monitoredLinkOutputs(m, d, monitoredLink, out);
  // energy balance, contacts carrying force, the largest joint deformation
  const int n = m.chain.links;
  out.energy = energyTerms(m, d, y);
  out.contacts = 0;
  for (int i = 0; i < d.nContacts; ++i) out.contacts += d.contacts[i].fN > 0.0 ? 1 : 0;
  out.maxJointDeformation = 0.0;
  for (int j = 0; j < n; ++j) out.maxJointDeformation = std::max(out.maxJointDeformation, d.joints.deformation[j]);
}

}  // namespace chaindrive
