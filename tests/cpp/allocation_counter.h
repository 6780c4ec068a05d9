// Counting heap allocations in the test binary: malloc, calloc and realloc forward to glibc's
// implementations and count calls while counting is on (Eigen allocates through malloc, operator
// new ends in malloc too). Available with glibc and without sanitizers (they bring their own
// malloc); tests skip themselves elsewhere.
#pragma once

#include <functional>

namespace chaindrive::test {

bool allocationCountingAvailable();
/// Number of heap allocations made while running f.
long countAllocations(const std::function<void()>& f);

}  // namespace chaindrive::test
