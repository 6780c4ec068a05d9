// Value references and variables of ChainDrive.fmu. This mirrors
// modelDescription/modelDescription.xml, the single source of variable names, value references,
// types, causalities and start values; tests/python/test_fmu.py fails if the two disagree.
#pragma once

#include "variable.h"

namespace chaindrive::fmu {

constexpr const char* kGuid = "{b6f8c2a4-7d1e-4f3a-9e2b-5c8d1a0f4e21}";
constexpr const char* kModelIdentifier = "ChainDrive";

enum Vr : unsigned {
  // inputs
  kCrankshaftW = 1,
  kCamshaftIntakeTau = 2,
  kCamshaftExhaustTau = 3,
  kTensionerSupplyPressure = 4,
  // outputs
  kCrankshaftPhi = 10,
  kCrankshaftTau = 11,
  kCamshaftIntakePhi = 12,
  kCamshaftIntakeW = 13,
  kCamshaftExhaustPhi = 14,
  kCamshaftExhaustW = 15,
  kTensionGuidePhi = 16,
  kTensionGuideW = 17,
  kTensionerF = 18,
  kTensionerS = 19,
  kTensionerV = 20,
  kChainFtight = 21,
  kChainFslack = 22,
  kLinkF = 23,
  kLinkFn = 24,
  kLinkFnSprocket = 25,
  kLinkFnGuide = 26,
  kLinkX = 27,
  kLinkY = 28,
  kEnergyKinetic = 29,
  kEnergyElastic = 30,
  kEnergyDissipated = 31,
  kEnergyInput = 32,
  kChainMaxJointDeformation = 33,
  kSolverTime = 34,
  kContacts = 40,
  kSolverSteps = 41,
  kTensionerChamberPressure = 42,
  kTensionerCheckValveFlow = 43,
  kTensionerLeakFlow = 44,
  // parameters
  kDriveFile = 100,
  kLinkIndex = 101,
  kSolverMethod = 102,
  kSolverTolerance = 103,
  kSolverStep = 104,
  kSolverPreload = 105,
  kContactMethod = 106,
  kChainJointModel = 107,
  kFidelity = 108,
  kSolverNewmarkGamma = 109,
  kTensionerPreload = 110,
  kTensionerStiffness = 111,
  kTensionerDamping = 112,
  kTensionerDampingExtension = 113,
  kTensionerOilTemperature = 114,
};

// clang-format off
constexpr Variable kVariables[] = {
  {"crankshaft.w",               kCrankshaftW,              Type::Real,    Causality::Input,     "314.1592653589793"},
  {"camshaftIntake.tau",         kCamshaftIntakeTau,        Type::Real,    Causality::Input,     "0"},
  {"camshaftExhaust.tau",        kCamshaftExhaustTau,       Type::Real,    Causality::Input,     "0"},
  {"crankshaft.phi",             kCrankshaftPhi,            Type::Real,    Causality::Output,    ""},
  {"crankshaft.tau",             kCrankshaftTau,            Type::Real,    Causality::Output,    ""},
  {"camshaftIntake.phi",         kCamshaftIntakePhi,        Type::Real,    Causality::Output,    ""},
  {"camshaftIntake.w",           kCamshaftIntakeW,          Type::Real,    Causality::Output,    ""},
  {"camshaftExhaust.phi",        kCamshaftExhaustPhi,       Type::Real,    Causality::Output,    ""},
  {"camshaftExhaust.w",          kCamshaftExhaustW,         Type::Real,    Causality::Output,    ""},
  {"tensionGuide.phi",           kTensionGuidePhi,          Type::Real,    Causality::Output,    ""},
  {"tensionGuide.w",             kTensionGuideW,            Type::Real,    Causality::Output,    ""},
  {"tensioner.F",                kTensionerF,               Type::Real,    Causality::Output,    ""},
  {"tensioner.s",                kTensionerS,               Type::Real,    Causality::Output,    ""},
  {"tensioner.v",                kTensionerV,               Type::Real,    Causality::Output,    ""},
  {"chain.Ftight",               kChainFtight,              Type::Real,    Causality::Output,    ""},
  {"chain.Fslack",               kChainFslack,              Type::Real,    Causality::Output,    ""},
  {"link.F",                     kLinkF,                    Type::Real,    Causality::Output,    ""},
  {"link.Fn",                    kLinkFn,                   Type::Real,    Causality::Output,    ""},
  {"link.FnSprocket",            kLinkFnSprocket,           Type::Real,    Causality::Output,    ""},
  {"link.FnGuide",               kLinkFnGuide,              Type::Real,    Causality::Output,    ""},
  {"link.x",                     kLinkX,                    Type::Real,    Causality::Output,    ""},
  {"link.y",                     kLinkY,                    Type::Real,    Causality::Output,    ""},
  {"energy.kinetic",             kEnergyKinetic,            Type::Real,    Causality::Output,    ""},
  {"energy.elastic",             kEnergyElastic,            Type::Real,    Causality::Output,    ""},
  {"energy.dissipated",          kEnergyDissipated,         Type::Real,    Causality::Output,    ""},
  {"energy.input",               kEnergyInput,              Type::Real,    Causality::Output,    ""},
  {"chain.maxJointDeformation",  kChainMaxJointDeformation, Type::Real,    Causality::Output,    ""},
  {"contacts",                   kContacts,                 Type::Integer, Causality::Output,    ""},
  {"solver.steps",               kSolverSteps,              Type::Integer, Causality::Output,    ""},
  {"solver.time",                kSolverTime,               Type::Real,    Causality::Output,    ""},
  {"driveFile",                  kDriveFile,                Type::String,  Causality::Parameter, ""},
  {"link.index",                 kLinkIndex,                Type::Integer, Causality::Parameter, "-1"},
  {"solver.method",              kSolverMethod,             Type::String,  Causality::Parameter, ""},
  {"solver.tolerance",           kSolverTolerance,          Type::Real,    Causality::Parameter, "1e-5"},
  {"solver.step",                kSolverStep,               Type::Real,    Causality::Parameter, "0"},
  {"solver.preload",             kSolverPreload,            Type::Boolean, Causality::Parameter, "true"},
  {"tensioner.preload",          kTensionerPreload,         Type::Real,    Causality::Parameter, "-1"},
  {"tensioner.stiffness",        kTensionerStiffness,       Type::Real,    Causality::Parameter, "-1"},
  {"tensioner.damping",          kTensionerDamping,         Type::Real,    Causality::Parameter, "-1"},
  {"tensioner.dampingExtension", kTensionerDampingExtension, Type::Real,   Causality::Parameter, "-1"},
  {"contact.method",             kContactMethod,            Type::String,  Causality::Parameter, ""},
  {"chain.jointModel",           kChainJointModel,          Type::String,  Causality::Parameter, ""},
  {"fidelity",                   kFidelity,                 Type::String,  Causality::Parameter, "link"},
  {"solver.newmarkGamma",        kSolverNewmarkGamma,       Type::Real,    Causality::Parameter, "0.5"},
  {"tensioner.supplyPressure",   kTensionerSupplyPressure,  Type::Real,    Causality::Input,     "300000"},
  {"tensioner.chamberPressure",  kTensionerChamberPressure, Type::Real,    Causality::Output,    ""},
  {"tensioner.checkValveFlow",   kTensionerCheckValveFlow,  Type::Real,    Causality::Output,    ""},
  {"tensioner.leakFlow",         kTensionerLeakFlow,        Type::Real,    Causality::Output,    ""},
  {"tensioner.oilTemperature",   kTensionerOilTemperature,  Type::Real,    Causality::Parameter, "363.15"},
};
// clang-format on

inline const Variable* findVariable(unsigned vr) { return findIn(kVariables, vr); }

}  // namespace chaindrive::fmu
