// The contract between the FMI 2.0 protocol and a model adapter (fmu/<adapter>/), in code: the
// hooks every model adapter provides, one line each. A model adapter derives from
// SimulationAdapter<itself, its number of Real inputs> (simulation_adapter.h), which calls these
// hooks and gives the protocol what it calls; Instance (instance.h) and the FMI functions
// (fmi2_functions.h) take their adapter as a CHAINDRIVE_MODEL_ADAPTER. Dispatch is static: no
// virtual call anywhere, fmi2DoStep included.
//
// A concept needs C++20, and the FMUs are C++17 (as the solver core, and as the source FMU's
// BUILDING.txt asks, harness/package/sources.py): there CHAINDRIVE_MODEL_ADAPTER is a plain type
// parameter and the same code compiles unchecked. The CMake build compiles each FMU's FMI
// functions once more as C++20 (its <FMU>_contract target), so every change of an adapter or of
// this list is checked there.
#pragma once

#include <string>

#include "host.h"
#include "simulation_adapter.h"
#include "variable.h"

#if __cplusplus >= 202002L
#include <concepts>

namespace chaindrive::fmu {

template <class A>
concept ModelAdapter =
    // a SimulationAdapter over itself (what the protocol calls), made with its instance's Host
    std::derived_from<A, SimulationAdapter<A, A::kInputs>> && std::constructible_from<A, Host&> &&
    requires(A& a, const A& c, unsigned vr, double& real, int& integer, const Variable& v, const char* guid) {
      // what the FMU is
      { c.findVariable(vr) } -> std::same_as<const Variable*>;  // the variable of a value reference; nullptr if none
      { c.modelIdentifier() } -> std::convertible_to<const char*>;  // its model description's
      { a.instantiated(guid) } -> std::same_as<bool>;  // after construction: the GUID checked (and the
                                                       // interface loaded); false: the problem logged
      { A::kSolverTime } -> std::convertible_to<unsigned>;   // the value references the protocol
      { A::kSolverSteps } -> std::convertible_to<unsigned>;  // answers itself
      { A::kModelWord } -> std::convertible_to<const char*>;  // what its descriptions describe, for messages
      { A::kStateMagic } -> std::same_as<const char (&)[8]>;  // the first bytes of its serialized FMU states
      // the steps of SimulationAdapter::prepare()
      { a.parametersValid() } -> std::same_as<bool>;  // every parameter problem logged; false if there was one
      { a.buildModel() } -> std::same_as<bool>;       // model_ from the parameters; false: a problem, logged
      { a.startSimulation() } -> std::same_as<void>;  // sim_ at its start state at host_.time(), then runStarted()
      { a.resetSettings() } -> std::same_as<void>;    // parameters and inputs to their start values
      // the simulation's inputs and outputs
      { a.applyInputs() } -> std::same_as<void>;      // in_ into sim_'s held inputs (no simulation: nothing)
      { a.evaluateOutputs() } -> std::same_as<void>;  // the outputs at sim_'s state, for the two readers below
      // values by value reference (nullptr or false: vr is not one of that kind)
      { a.realSetting(vr) } -> std::same_as<double*>;               // a Real parameter or input
      { a.stringParameter(vr) } -> std::same_as<std::string*>;      // a String parameter
      { a.integerParameter(vr) } -> std::same_as<int*>;             // an Integer parameter
      { a.booleanParameter(vr) } -> std::same_as<bool*>;            // a Boolean parameter
      { c.readRealOutput(vr, real) } -> std::same_as<bool>;         // a Real output of the adapter's
      { c.readIntegerOutput(vr, integer) } -> std::same_as<bool>;   // an Integer output of the adapter's
      { a.inputAcceptable(v, real) } -> std::same_as<bool>;         // false (logged): an input out of its range
    };

}  // namespace chaindrive::fmu

#define CHAINDRIVE_MODEL_ADAPTER chaindrive::fmu::ModelAdapter
#else
#define CHAINDRIVE_MODEL_ADAPTER class
#endif
