#include "simd.h"

#if defined(__x86_64__) || defined(_M_X64)
#include <cpuid.h>
#endif

namespace chaindrive::simd {

namespace {

#if defined(__x86_64__) || defined(_M_X64)
bool askCpuForAvx2() {
  unsigned a = 0, b = 0, c = 0, d = 0;
  if (!__get_cpuid(1, &a, &b, &c, &d)) return false;
  const bool osSavesExtendedState = c & (1u << 27), avx = c & (1u << 28);
  if (!osSavesExtendedState || !avx) return false;
  // XCR0 bits 1 and 2: the operating system saves the SSE and AVX registers on a context switch
  unsigned xcr0Low = 0, xcr0High = 0;
  __asm__("xgetbv" : "=a"(xcr0Low), "=d"(xcr0High) : "c"(0));
  if ((xcr0Low & 6u) != 6u) return false;
  if (__get_cpuid_max(0, nullptr) < 7) return false;
  __cpuid_count(7, 0, a, b, c, d);
  return b & (1u << 5);
}
#else
bool askCpuForAvx2() { return false; }
#endif

}  // namespace

bool hasAvx2() {
  // (a constant of the process, initialized once and thread-safely; CPUID itself is slow in a
  // virtual machine, where it traps to the hypervisor)
  static const bool avx2 = askCpuForAvx2();
  return avx2;
}

}  // namespace chaindrive::simd
