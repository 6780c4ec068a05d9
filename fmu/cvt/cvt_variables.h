// Value references and variables of CVTChain.fmu. This mirrors modelDescription/CVTChain.xml,
// the single source of variable names, value references, types, causalities and start values;
// tests/python/fmu/test_cvt_fmu.py fails if the two disagree.
#pragma once

#include "variable.h"

namespace chaindrive::fmu {

constexpr const char* kGuid = "{3f9a7c21-5b8e-4d62-a1f4-8e2c6b0d9a57}";
constexpr const char* kModelIdentifier = "CVTChain";

enum Vr : unsigned {
  // inputs
  kDrivingPulleyW = 1,
  kDrivenPulleyTauLoad = 2,
  kRatio = 3,
  // outputs
  kDrivingPulleyPhi = 10,
  kDrivingPulleyTau = 11,
  kDrivenPulleyPhi = 12,
  kDrivenPulleyW = 13,
  kDrivenPulleyTau = 14,
  kSlip = 15,
  kChainFtight = 16,
  kChainFslack = 17,
  kDrivingPulleyFclamp = 18,
  kDrivenPulleyFclamp = 19,
  kPowerLoss = 20,
  kPinFn = 21,
  kPinFfrictionRadial = 22,
  kPinFfrictionCircumferential = 23,
  kLinkF = 24,
  kEnergyKinetic = 25,
  kEnergyElastic = 26,
  kEnergyDissipated = 27,
  kEnergyInput = 28,
  kSolverTime = 34,
  kContacts = 40,
  kSolverSteps = 41,
  kPinPulley = 42,
  // parameters
  kCvtFile = 100,
  kLinkIndex = 101,
  kSolverMethod = 102,
  kSolverTolerance = 103,
  kSolverStep = 104,
  kClampingForce = 106,
};

// clang-format off
constexpr Variable kVariables[] = {
  {"drivingPulley.w",                kDrivingPulleyW,              Type::Real,    Causality::Input,     "209.43951023931953"},
  {"drivenPulley.tauLoad",           kDrivenPulleyTauLoad,         Type::Real,    Causality::Input,     "0"},
  {"ratio",                          kRatio,                       Type::Real,    Causality::Input,     "1"},
  {"drivingPulley.phi",              kDrivingPulleyPhi,            Type::Real,    Causality::Output,    ""},
  {"drivingPulley.tau",              kDrivingPulleyTau,            Type::Real,    Causality::Output,    ""},
  {"drivenPulley.phi",               kDrivenPulleyPhi,             Type::Real,    Causality::Output,    ""},
  {"drivenPulley.w",                 kDrivenPulleyW,               Type::Real,    Causality::Output,    ""},
  {"drivenPulley.tau",               kDrivenPulleyTau,             Type::Real,    Causality::Output,    ""},
  {"slip",                           kSlip,                        Type::Real,    Causality::Output,    ""},
  {"chain.Ftight",                   kChainFtight,                 Type::Real,    Causality::Output,    ""},
  {"chain.Fslack",                   kChainFslack,                 Type::Real,    Causality::Output,    ""},
  {"drivingPulley.Fclamp",           kDrivingPulleyFclamp,         Type::Real,    Causality::Output,    ""},
  {"drivenPulley.Fclamp",            kDrivenPulleyFclamp,          Type::Real,    Causality::Output,    ""},
  {"powerLoss",                      kPowerLoss,                   Type::Real,    Causality::Output,    ""},
  {"pin.Fn",                         kPinFn,                       Type::Real,    Causality::Output,    ""},
  {"pin.FfrictionRadial",            kPinFfrictionRadial,          Type::Real,    Causality::Output,    ""},
  {"pin.FfrictionCircumferential",   kPinFfrictionCircumferential, Type::Real,    Causality::Output,    ""},
  {"link.F",                         kLinkF,                       Type::Real,    Causality::Output,    ""},
  {"energy.kinetic",                 kEnergyKinetic,               Type::Real,    Causality::Output,    ""},
  {"energy.elastic",                 kEnergyElastic,               Type::Real,    Causality::Output,    ""},
  {"energy.dissipated",              kEnergyDissipated,            Type::Real,    Causality::Output,    ""},
  {"energy.input",                   kEnergyInput,                 Type::Real,    Causality::Output,    ""},
  {"contacts",                       kContacts,                    Type::Integer, Causality::Output,    ""},
  {"pin.pulley",                     kPinPulley,                   Type::Integer, Causality::Output,    ""},
  {"solver.steps",                   kSolverSteps,                 Type::Integer, Causality::Output,    ""},
  {"solver.time",                    kSolverTime,                  Type::Real,    Causality::Output,    ""},
  {"cvtFile",                        kCvtFile,                     Type::String,  Causality::Parameter, ""},
  {"link.index",                     kLinkIndex,                   Type::Integer, Causality::Parameter, "-1"},
  {"solver.method",                  kSolverMethod,                Type::String,  Causality::Parameter, "fixed-verlet"},
  {"solver.tolerance",               kSolverTolerance,             Type::Real,    Causality::Parameter, "1e-5"},
  {"solver.step",                    kSolverStep,                  Type::Real,    Causality::Parameter, "5e-7"},
  {"clampingForce",                  kClampingForce,               Type::Real,    Causality::Parameter, "-1"},
};
// clang-format on

inline const Variable* findVariable(unsigned vr) { return findIn(kVariables, vr); }

}  // namespace chaindrive::fmu
