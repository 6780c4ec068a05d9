// Vectors of doubles for the per-link loops of the dynamics (GCC's and Clang's vector
// extensions): W lanes, each lane computed with the same IEEE operations in the same order as a
// scalar double, so that a loop gives the same bits with 1, 2 (SSE2) or 4 (AVX2) lanes. What keeps
// it so: no fused multiply-add (the library is built with -ffp-contract=off and the AVX2 loops
// are compiled without FMA), no reassociation, and sums across lanes always formed in the same
// order (reduce4). The laws written once for a double and for a vector (the joint law, the sines
// and cosines) use the overloads below, which exist for both.
#pragma once

#include <cmath>
#include <cstring>

#define CHAINDRIVE_ALWAYS_INLINE inline __attribute__((always_inline))

// Code for AVX2 (without FMA) beside the baseline of every x86-64 CPU (SSE2), chosen at run time
// by hasAvx2(). Elsewhere (a source build on another architecture) both are the baseline.
#if defined(__x86_64__) || defined(_M_X64)
#define CHAINDRIVE_TARGET_AVX2 __attribute__((target("avx2")))
#else
#define CHAINDRIVE_TARGET_AVX2
#endif

/// A function `name` with the parameters `params` whose body is the always-inlined function
/// name##Body called with `args`, compiled twice, for AVX2 and for the baseline, the copy chosen
/// by hasAvx2() at every call. (GCC's target_clones does this with ifunc, which Windows and
/// Clang's linkers for it do not have.)
#define CHAINDRIVE_DISPATCH_BY_CPU(ret, name, params, args)                  \
  CHAINDRIVE_TARGET_AVX2 static ret name##Avx2 params { return name##Body args; } \
  static ret name##Baseline params { return name##Body args; }                   \
  ret name params { return ::chaindrive::simd::hasAvx2() ? name##Avx2 args : name##Baseline args; }

namespace chaindrive::simd {

/// True where the CPU has AVX2 and the operating system saves its registers (asked once per
/// process; the answer never changes).
bool hasAvx2();

/// The vector types of W lanes: doubles, the masks comparisons give, and 32-bit integers.
template <int W>
struct Lanes;
template <>
struct Lanes<2> {
  typedef double V __attribute__((vector_size(16)));
  typedef decltype(V{} < V{}) Mask;  // (64-bit integers, set lanes -1)
  typedef int Int __attribute__((vector_size(8)));
};
template <>
struct Lanes<4> {
  typedef double V __attribute__((vector_size(32)));
  typedef decltype(V{} < V{}) Mask;
  typedef int Int __attribute__((vector_size(16)));
};

template <class V>
constexpr int lanesOf() {
  return static_cast<int>(sizeof(V) / sizeof(double));
}

template <class V>
CHAINDRIVE_ALWAYS_INLINE V load(const double* p) {
  V v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
template <class V>
CHAINDRIVE_ALWAYS_INLINE void store(double* p, V v) {
  std::memcpy(p, &v, sizeof v);
}
/// A loop's access to arrays of doubles, one vector at i at a time: all its lanes ...
template <class V>
struct AllLanes {
  CHAINDRIVE_ALWAYS_INLINE V load(const double* p) const { return simd::load<V>(p); }
  CHAINDRIVE_ALWAYS_INLINE void store(double* p, V v) const { simd::store(p, v); }
};
/// ... or the first `count` (its last, partly filled vector): zeros read in the others, nothing
/// read or stored past them.
template <class V>
struct FirstLanes {
  int count;
  CHAINDRIVE_ALWAYS_INLINE V load(const double* p) const {
    V v = {};
    for (int l = 0; l < count; ++l) v[l] = p[l];
    return v;
  }
  CHAINDRIVE_ALWAYS_INLINE void store(double* p, V v) const {
    for (int l = 0; l < count; ++l) p[l] = v[l];
  }
};

/// Calls body(i, lanes) for i = 0, W, 2 W, ... below n: lanes is AllLanes for the whole vectors,
/// FirstLanes for a last, partly filled one (the body is compiled for each: the whole vectors'
/// loop has no test per lane). The body must be always inlined. forEachVectorIn: the same from
/// `first` (a multiple of W) below `last`.
template <class V, class Body>
CHAINDRIVE_ALWAYS_INLINE void forEachVectorIn(int first, int last, Body body) {
  constexpr int W = lanesOf<V>();
  int i = first;
  for (; i + W <= last; i += W) body(i, AllLanes<V>{});
  if (i < last) body(i, FirstLanes<V>{last - i});
}

template <class V, class Body>
CHAINDRIVE_ALWAYS_INLINE void forEachVector(int n, Body body) {
  forEachVectorIn<V>(0, n, body);
}

/// Every lane x.
template <class V>
CHAINDRIVE_ALWAYS_INLINE V splat(double x) {
  V v;
  for (int l = 0; l < lanesOf<V>(); ++l) v[l] = x;
  return v;
}

/// a where the mask is set, b elsewhere (the scalar overload: a where m is true).
template <class V, class M>
CHAINDRIVE_ALWAYS_INLINE V select(M m, V a, V b) {
  return (V)(((M)a & m) | ((M)b & ~m));
}
CHAINDRIVE_ALWAYS_INLINE double select(bool m, double a, double b) { return m ? a : b; }

/// a with its sign flipped where the mask is set.
template <class V, class M>
CHAINDRIVE_ALWAYS_INLINE V flipSign(M m, V a) {
  return (V)((M)a ^ (m & (M)splat<V>(-0.0)));
}

/// |v| lane by lane (the sign bit cleared; the scalar overload: std::fabs).
template <class V>
CHAINDRIVE_ALWAYS_INLINE V abs(V v) {
  typedef long long Bits __attribute__((vector_size(sizeof(V))));
  return (V)((Bits)v & ~(Bits)splat<V>(-0.0));
}
CHAINDRIVE_ALWAYS_INLINE double abs(double v) { return std::fabs(v); }

/// The lanes of a vector in another order: lanes 1, 0, 3, 2 (the pairs swapped) and 2, 3, 0, 1
/// (the halves swapped), and from two vectors a and b the lanes a0, b0, a2, b2 (every even lane
/// of each). Clang and GCC from 12 have __builtin_shufflevector with constant indices; older GCC
/// (a source build on an older system) only __builtin_shuffle with a vector of indices.
#if defined(__clang__) || __GNUC__ >= 12
template <class V>
CHAINDRIVE_ALWAYS_INLINE V swapPairs(V v) {
  if constexpr (lanesOf<V>() == 4) return __builtin_shufflevector(v, v, 1, 0, 3, 2);
  else return __builtin_shufflevector(v, v, 1, 0);
}
template <class V>
CHAINDRIVE_ALWAYS_INLINE V swapHalves(V v) {
  return __builtin_shufflevector(v, v, 2, 3, 0, 1);
}
template <class V>
CHAINDRIVE_ALWAYS_INLINE V evenLanes(V a, V b) {
  if constexpr (lanesOf<V>() == 4) return __builtin_shufflevector(a, b, 0, 4, 2, 6);
  else return __builtin_shufflevector(a, b, 0, 2);
}
#else
template <class V>
CHAINDRIVE_ALWAYS_INLINE V swapPairs(V v) {
  typedef decltype(V{} < V{}) Index;
  if constexpr (lanesOf<V>() == 4) return __builtin_shuffle(v, Index{1, 0, 3, 2});
  else return __builtin_shuffle(v, Index{1, 0});
}
template <class V>
CHAINDRIVE_ALWAYS_INLINE V swapHalves(V v) {
  typedef decltype(V{} < V{}) Index;
  return __builtin_shuffle(v, Index{2, 3, 0, 1});
}
template <class V>
CHAINDRIVE_ALWAYS_INLINE V evenLanes(V a, V b) {
  typedef decltype(V{} < V{}) Index;
  if constexpr (lanesOf<V>() == 4) return __builtin_shuffle(a, b, Index{0, 4, 2, 6});
  else return __builtin_shuffle(a, b, Index{0, 2});
}
#endif

/// Every lane of the mask combined with every other by op (& or |), by swapping halves: no lane
/// is extracted one at a time.
template <class M, class Op>
CHAINDRIVE_ALWAYS_INLINE M foldLanes(M m, Op op) {
  if constexpr (sizeof(M) == 32) m = op(m, swapHalves(m));
  return op(m, swapPairs(m));
}
/// True when every lane of the mask is set.
template <class M>
CHAINDRIVE_ALWAYS_INLINE bool allSet(M m) {
  return foldLanes(m, [](M a, M b) __attribute__((always_inline)) { return a & b; })[0] != 0;
}
/// True when some lane of the mask is set.
template <class M>
CHAINDRIVE_ALWAYS_INLINE bool anySet(M m) {
  return foldLanes(m, [](M a, M b) __attribute__((always_inline)) { return a | b; })[0] != 0;
}

/// Square root lane by lane (correctly rounded: the same bits as std::sqrt of each lane).
template <class V>
CHAINDRIVE_ALWAYS_INLINE V sqrt(V v) {
  for (int l = 0; l < lanesOf<V>(); ++l) v[l] = std::sqrt(v[l]);
  return v;
}
CHAINDRIVE_ALWAYS_INLINE double sqrt(double v) { return std::sqrt(v); }

/// Sum of four partial sums in one fixed order: sums over the links are kept in four partial
/// sums (link i in sum i mod 4) whatever the vector width, then combined here.
CHAINDRIVE_ALWAYS_INLINE double reduce4(const double s[4]) { return ((s[0] + s[1]) + s[2]) + s[3]; }

/// The four partial sums kept in vectors of W lanes (sum h W + l in lane l of partial[h]) into
/// one, by reduce4.
template <int W>
CHAINDRIVE_ALWAYS_INLINE double reducePartials(const typename Lanes<W>::V (&partial)[4 / W]) {
  double sums[4];
  for (int h = 0; h < 4 / W; ++h)
    for (int l = 0; l < W; ++l) sums[h * W + l] = partial[h][l];
  return reduce4(sums);
}

}  // namespace chaindrive::simd
