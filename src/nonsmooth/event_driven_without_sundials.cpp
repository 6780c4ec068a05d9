// The event-driven method in a build without SUNDIALS (the FMUs' source build, harness/package):
// its smooth phases need ARKODE, so it is refused by name when the model starts.
#include <stdexcept>

#include "nonsmooth/event_driven.h"

namespace chaindrive::ns {

struct EventDriven::Sundials {};

EventDriven::EventDriven(NonsmoothSystem& sys, const EventDrivenSettings& s)
    : NonsmoothMethod(0), sys_(sys), settings_(s), minv_(sys.inverseMass()), n_(0) {
  throw std::invalid_argument(
      "contact.method 'event-driven' needs SUNDIALS (ARKODE integrates its smooth phases), which this build does "
      "not have (a build from the FMU's sources/, which carry no SUNDIALS); time-stepping does not");
}
EventDriven::~EventDriven() = default;
void EventDriven::reset(double, const double*, const double*) {}
void EventDriven::advance(double) {}
int EventDriven::rhs(double, const double*, double*) noexcept { return -1; }
int EventDriven::roots(double, const double*, double*) noexcept { return -1; }

}  // namespace chaindrive::ns
