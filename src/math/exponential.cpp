// exp, log and pow (src/math/elementary.h). exp: fdlibm's method (FreeBSD msun e_exp.c), its
// core shared with pow, which needs exp of a double-double. log: a table-driven reduction and a
// series, all in double-double (pow needs log(x) to far more than 53 bits: an error e in
// y log(x) becomes a relative error e of the power, and |y log(x)| reaches 745).
#include <cmath>
#include <cstdint>
#include <limits>

#include "math/double_double.h"
#include "math/elementary.h"

namespace chaindrive::math {
namespace {

using detail::DoubleDouble;
using detail::kInfinity;

constexpr double kLn2Hi = 6.93147180369123816490e-01;  // ln 2 in two parts, the first of 32 bits:
constexpr double kLn2Lo = 1.90821492927058770002e-10;  // k kLn2Hi is exact for |k| < 2^21
constexpr double kInvLn2 = 1.44269504088896338700e+00;

/// y 2^k for y in about [0.7, 1.5] and -1076 <= k <= 1024, rounded once (where the result is
/// subnormal or overflows)
double scaleByPowerOfTwo(double y, int k) {
  if (k > 1023) return y * 2.0 * detail::powerOfTwo(k - 1);
  if (k < -1022) return y * detail::powerOfTwo(k + 1000) * detail::powerOfTwo(-1000);
  return y * detail::powerOfTwo(k);
}

/// exp(x + tail) for -745.2 <= x <= 709.8 and |tail| < 2^-30 (e_exp.c): x = k ln2 + r with
/// r = hi - lo (hi exact), exp(r) = 1 + r + r c / (2 - c) with c = r - r^2 P(r^2) (P: fdlibm's
/// P1..P5, Remez error below 2^-59); 1 + hi + (that rest - lo) summed without error, rounded once
double expOfSum(double x, double tail) {
  constexpr double P1 = 1.66666666666666019037e-01, P2 = -2.77777777770155933842e-03,
                   P3 = 6.61375632143793436117e-05, P4 = -1.65339022054652515390e-06,
                   P5 = 4.13813679705723846039e-08;
  const int k = static_cast<int>(x * kInvLn2 + (x < 0.0 ? -0.5 : 0.5));
  const double kd = k;
  const double hi = x - kd * kLn2Hi;  // exact (Sterbenz: x and k kLn2Hi within a factor 2)
  const double lo = kd * kLn2Lo - tail;
  const double r = hi - lo, z = r * r, z2 = z * z;
  const double c = r - z * ((P1 + z * P2) + z2 * ((P3 + z * P4) + z2 * P5));  // (Estrin: a short chain)
  const DoubleDouble sum = detail::twoSum(hi, (r * c) / (2.0 - c) - lo);
  const DoubleDouble withOne = detail::fastTwoSum(1.0, sum.hi);  // |sum.hi| < 1/2
  return scaleByPowerOfTwo(withOne.hi + (withOne.lo + sum.lo), k);
}

/// one interval of the log reduction: c ~ 1/m on a 2^-24 grid (25 significant bits or fewer) and
/// log(1/c) in two doubles
struct LogEntry {
  double c;
  double logHi;
  double logLo;
};

// m in [m0, 2 m0), m0 = 1 - 75.5/256 = 0x1.69p-1, in 128 intervals: 2^-8 wide below 1, 2^-7
// above, centred on the c_i, and one from 1 - 2^-9 to 1 + 2^-8 with c = 1 (x near 1: no
// cancellation); |m c - 1| <= 2^-8 everywhere. From exact rationals and 60-digit logarithms:
//   python3 -c '
//   from decimal import Decimal, getcontext; from fractions import Fraction as F; getcontext().prec = 60
//   for i in range(128):
//       lo, width = (1 - F(755, 2560) + F(i, 256), F(1, 256)) if i < 75 else (1 + F(2 * i - 151, 256), F(1, 128))
//       c = F(1) if i == 75 else F(round(2 ** 24 / (lo + width / 2)), 2 ** 24)
//       L = Decimal(c.denominator).ln() - Decimal(c.numerator).ln(); h = float(L)
//       print("{%s, %s, %s}," % (float(c).hex(), h.hex(), float(L - Decimal(h)).hex()))'
constexpr LogEntry kLogTable[128] = {
    {0x1.6a13cdp+0, -0x1.63003077aac49p-2, -0x1.f6319c926bf33p-58},
    {0x1.681681p+0, -0x1.5d5bdccd95f2dp-2, 0x1.741169c5e3544p-60},
    {0x1.661ec7p+0, -0x1.57bf76408d1f9p-2, 0x1.8a08ce945d616p-57},
    {0x1.642c86p+0, -0x1.522ae1b38a3d5p-2, 0x1.47bf4b01a8a1cp-56},
    {0x1.623fa7p+0, -0x1.4c9e089d72c39p-2, 0x1.150d88204cea2p-56},
    {0x1.605816p+0, -0x1.4718dc171c41bp-2, -0x1.0fb4c14b01999p-60},
    {0x1.5e75bcp+0, -0x1.419b438d5e8c4p-2, 0x1.41226ae02c643p-56},
    {0x1.5c9883p+0, -0x1.3c25284333182p-2, -0x1.8d2d82666c68dp-56},
    {0x1.5ac057p+0, -0x1.36b67857e1115p-2, -0x1.cdd87ad2bb289p-57},
    {0x1.58ed23p+0, -0x1.314f1e0535ce4p-2, 0x1.4f69909ea43dcp-56},
    {0x1.571ed4p+0, -0x1.2bef087dc9353p-2, 0x1.4adad78e9b5dep-56},
    {0x1.555555p+0, -0x1.269620134db9p-2, -0x1.e0efac8485ad1p-56},
    {0x1.539095p+0, -0x1.21445824eb8d1p-2, 0x1.20a8b408fe7b2p-56},
    {0x1.51d07fp+0, -0x1.1bf9972da6b93p-2, 0x1.6aeb5d5a3cd5p-61},
    {0x1.501501p+0, -0x1.16b5cbc6cfb72p-2, 0x1.dd842e9c4bc23p-56},
    {0x1.4e5e0ap+0, -0x1.1178e6c27e478p-2, -0x1.6338a64271d5p-58},
    {0x1.4cab88p+0, -0x1.0c42d516162dfp-2, -0x1.258b1afe1ef18p-56},
    {0x1.4afd6ap+0, -0x1.071385f4d5862p-2, -0x1.c5b16ed4d3be3p-56},
    {0x1.49539ep+0, -0x1.01eae4aa6c69p-2, 0x1.141487e43eecap-58},
    {0x1.47ae14p+0, -0x1.f991c3cb3b37p-3, -0x1.f664fd6f98079p-57},
    {0x1.460cbcp+0, -0x1.ef5adb2dcffdcp-3, -0x1.aea97b9674356p-59},
    {0x1.446f86p+0, -0x1.e530edde7100ep-3, 0x1.c762822b0494fp-57},
    {0x1.42d662p+0, -0x1.db13d8bd4893bp-3, 0x1.1dee339ef3e0fp-58},
    {0x1.414141p+0, -0x1.d1037d8655e79p-3, 0x1.2f9d6f2be390cp-57},
    {0x1.3fb014p+0, -0x1.c6ffbc8f00f71p-3, 0x1.9e58b2c54f9fap-57},
    {0x1.3e22ccp+0, -0x1.bd0874c3bd8abp-3, -0x1.fba6ac93f4d84p-57},
    {0x1.3c995ap+0, -0x1.b31d83a5bce39p-3, -0x1.78ac52cb7ac03p-57},
    {0x1.3b13b1p+0, -0x1.a93ed248ad9e1p-3, -0x1.795f517d2e402p-58},
    {0x1.3991c3p+0, -0x1.9f6c420889662p-3, 0x1.db97992514607p-57},
    {0x1.381381p+0, -0x1.95a5ac5f7017dp-3, -0x1.18589d09849c7p-59},
    {0x1.3698dfp+0, -0x1.8beafd1b8fe8ap-3, 0x1.7e2abba4a62e3p-57},
    {0x1.3521dp+0, -0x1.823c18551a3bep-3, 0x1.1232cbc613cdfp-57},
    {0x1.33ae46p+0, -0x1.7898da4444c6fp-3, -0x1.f3c7b9cb22e4fp-57},
    {0x1.323e35p+0, -0x1.6f012b2756ab6p-3, 0x1.51e5974e1167ep-57},
    {0x1.30d19p+0, -0x1.6574eb68c133ap-3, 0x1.3a69e1f36ee28p-57},
    {0x1.2f684cp+0, -0x1.5bf407b543db1p-3, 0x1.1f5b3f6b8a29ap-61},
    {0x1.2e025cp+0, -0x1.527e5e2a1b58dp-3, 0x1.38d4b41320354p-60},
    {0x1.2c9fb5p+0, -0x1.4913d9433b56p-3, 0x1.0aab01e32cdfp-57},
    {0x1.2b404bp+0, -0x1.3fb45ba1928cap-3, 0x1.a5f9a60746c09p-59},
    {0x1.29e413p+0, -0x1.365fcda15900fp-3, -0x1.2ea093354a23fp-57},
    {0x1.288b01p+0, -0x1.2d160fb068139p-3, 0x1.6dcd20027f206p-57},
    {0x1.27350cp+0, -0x1.23d715e49c1f7p-3, -0x1.471fd5840ded1p-59},
    {0x1.25e227p+0, -0x1.1aa2b7aa3f72ap-3, 0x1.45778ecf60d15p-58},
    {0x1.249249p+0, -0x1.1178e7227e47bp-3, 0x1.0e63a69ac713cp-58},
    {0x1.234568p+0, -0x1.08598e99e39fcp-3, 0x1.d6ffe1ed6a14bp-61},
    {0x1.21fb78p+0, -0x1.fe89129dbd565p-4, -0x1.4d82f752c5c5dp-60},
    {0x1.20b471p+0, -0x1.ec739b60a111bp-4, 0x1.235fc9d8dc6a6p-58},
    {0x1.1f7048p+0, -0x1.da727838446ap-4, -0x1.401fa7c1ddac2p-58},
    {0x1.1e2ef4p+0, -0x1.c885845bc4b1ap-4, -0x1.838cbbbf5119cp-58},
    {0x1.1cf06bp+0, -0x1.b6ac8afad5b1ap-4, 0x1.882bf69c2fd7bp-58},
    {0x1.1bb4a4p+0, -0x1.a4e763cb1bc38p-4, 0x1.7b5ca204397afp-58},
    {0x1.1a7b96p+0, -0x1.9335e4d594988p-4, -0x1.70eaf4f4bbbe8p-59},
    {0x1.194538p+0, -0x1.8197e2740e3fp-4, 0x1.1834803aef5ap-62},
    {0x1.181181p+0, -0x1.700d2f4eac0ep-4, -0x1.36a670c61e13ap-63},
    {0x1.16e069p+0, -0x1.5e95ab09791b8p-4, -0x1.61875983684afp-58},
    {0x1.15b1e6p+0, -0x1.4d31165207eacp-4, -0x1.ed3e85945daedp-59},
    {0x1.1485f1p+0, -0x1.3bdf5c4d1ee63p-4, 0x1.d4b448e34bb26p-58},
    {0x1.135c81p+0, -0x1.2aa04924717a4p-4, 0x1.6574e3c568fddp-60},
    {0x1.12358ep+0, -0x1.1973b6346554fp-4, -0x1.7aa7935cffc9ep-59},
    {0x1.111111p+0, -0x1.08598a59e3a06p-4, -0x1.147fb2d3f5bc3p-61},
    {0x1.0fef01p+0, -0x1.eea31a206b87bp-5, 0x1.849f92bd46cd9p-60},
    {0x1.0ecf57p+0, -0x1.ccb7449ddb2bdp-5, 0x1.f48fa69d79a9ap-59},
    {0x1.0db20bp+0, -0x1.aaef3b2fb10cap-5, -0x1.c9aa530dcadabp-60},
    {0x1.0c9715p+0, -0x1.894aa1c9fb343p-5, -0x1.28be97675f792p-60},
    {0x1.0b7e6fp+0, -0x1.67c9568d4bb4bp-5, 0x1.5fec1154444bep-59},
    {0x1.0a6811p+0, -0x1.466af802de3cdp-5, 0x1.5dd6de130be91p-59},
    {0x1.0953f4p+0, -0x1.252f4078d1811p-5, -0x1.5c05d0df52f35p-62},
    {0x1.084211p+0, -0x1.0415e79e7440cp-5, -0x1.80ba704ea692dp-60},
    {0x1.073261p+0, -0x1.c63d45014aab4p-6, 0x1.5602d109913cbp-60},
    {0x1.0624ddp+0, -0x1.8492470c8caaep-6, -0x1.cda4f65160658p-65},
    {0x1.05197fp+0, -0x1.432a739980c4ap-6, -0x1.ab2474ffebb05p-60},
    {0x1.041041p+0, -0x1.0205648935847p-6, -0x1.4f91d08032393p-61},
    {0x1.03091bp+0, -0x1.824461b88a244p-7, 0x1.8da7a5e367c78p-61},
    {0x1.020408p+0, -0x1.01014f588de6dp-7, -0x1.46662bec2797ap-62},
    {0x1.010101p+0, -0x1.0080549588b35p-8, -0x1.d96638cf4e121p-62},
    {0x1.0p+0, 0.0, 0.0},
    {0x1.fc07fp-1, 0x1.fe02b6b106791p-8, -0x1.e44b538c673f4p-67},
    {0x1.f81f82p-1, 0x1.fc0a890fc03e4p-7, 0x1.f3db4e851a025p-64},
    {0x1.f4465ap-1, 0x1.7b91acfd5b11cp-6, 0x1.893fa9f13608bp-61},
    {0x1.f07c2p-1, 0x1.f82990e78338p-6, 0x1.33e345a474878p-60},
    {0x1.ecc07cp-1, 0x1.39e86e1febd8dp-5, 0x1.c80a727d55e91p-60},
    {0x1.e9131ap-1, 0x1.77459be32dd23p-5, 0x1.58d3f33863dffp-59},
    {0x1.e573acp-1, 0x1.b42de091971d5p-5, 0x1.4a3464fc1289ep-59},
    {0x1.e1e1e2p-1, 0x1.f0a30a01162a7p-5, 0x1.85f3259b11022p-59},
    {0x1.de5d6ep-1, 0x1.1653710a37ae3p-4, 0x1.5312e2535944p-59},
    {0x1.dae608p-1, 0x1.341d7461bd1ddp-4, 0x1.29980db65a305p-60},
    {0x1.d77b66p-1, 0x1.51b06dd061852p-4, 0x1.593c4cf73c323p-59},
    {0x1.d41d42p-1, 0x1.6f0d272e56b4dp-4, -0x1.106d99604b992p-58},
    {0x1.d0cb58p-1, 0x1.8c3465e319b45p-4, 0x1.5acc0f5bb481ap-60},
    {0x1.cd8568p-1, 0x1.a926d8a4ad57p-4, -0x1.af42b3ab91a14p-60},
    {0x1.ca4b3p-1, 0x1.c5e54bf5bc748p-4, -0x1.a8a79e01fa78fp-58},
    {0x1.c71c72p-1, 0x1.e27074e2af2e8p-4, -0x1.615782ac8ac09p-60},
    {0x1.c3f8fp-1, 0x1.fec9141dbeabbp-4, 0x1.51728cfa743d2p-59},
    {0x1.c0e07p-1, 0x1.0d77e8cd08e5ap-3, 0x1.9a5dc63e58601p-57},
    {0x1.bdd2b8p-1, 0x1.1b72b012f67a8p-3, -0x1.1be7e76dbee7fp-57},
    {0x1.bacf92p-1, 0x1.29552c41ff52ep-3, -0x1.1fd1335a9aebep-58},
    {0x1.b7d6c4p-1, 0x1.371fc161e8f75p-3, -0x1.80c9a4ff5c905p-57},
    {0x1.b4e81cp-1, 0x1.44d2b38cb7d29p-3, -0x1.0585316b9acbp-60},
    {0x1.b20364p-1, 0x1.526e5e5a1b438p-3, -0x1.646ff8a44628fp-57},
    {0x1.af286cp-1, 0x1.5ff3060a793d5p-3, -0x1.bc60f05a71a18p-58},
    {0x1.ac5702p-1, 0x1.6d60fce19d21fp-3, -0x1.ab89f5149b2dap-63},
    {0x1.a98ef6p-1, 0x1.7ab890410d909p-3, 0x1.fe36b2d74b0b3p-59},
    {0x1.a6d01ap-1, 0x1.87fa08620c915p-3, -0x1.76ffb21ab1b22p-58},
    {0x1.a41a42p-1, 0x1.9525a80f456b8p-3, -0x1.e6fb3ff47272bp-57},
    {0x1.a16d4p-1, 0x1.a23bbffe2b567p-3, 0x1.9371105cfef01p-59},
    {0x1.9ec8eap-1, 0x1.af3c91880bffep-3, 0x1.e672e728be6fdp-58},
    {0x1.9c2d14p-1, 0x1.bc286be2d8cecp-3, -0x1.c818a4e19ccc6p-57},
    {0x1.99999ap-1, 0x1.c8ff7a79a9a26p-3, -0x1.4f68a22edeab4p-57},
    {0x1.970e5p-1, 0x1.d5c21434fbb98p-3, -0x1.91bbcf9d70802p-57},
    {0x1.948b1p-1, 0x1.e27075e2af2e7p-3, -0x1.61578157356b5p-59},
    {0x1.920fb4p-1, 0x1.ef0adfddc594p-3, 0x1.618e0df41b39bp-59},
    {0x1.8f9c18p-1, 0x1.fb918bd5e3e44p-3, -0x1.caaabca476ee8p-57},
    {0x1.8d3018p-1, 0x1.04025b6b4d04ap-2, -0x1.d1d80fc74adbfp-58},
    {0x1.8acb9p-1, 0x1.0a3250a7390fp-2, -0x1.0460195491c17p-57},
    {0x1.886e6p-1, 0x1.1058bd1ae4ae2p-2, -0x1.9d819228227f2p-56},
    {0x1.861862p-1, 0x1.1675c97aba611p-2, 0x1.1ce6397632e3p-57},
    {0x1.83c978p-1, 0x1.1c898b36999fdp-2, -0x1.f0e5c70fa9c6dp-56},
    {0x1.818182p-1, 0x1.22941e6cf7969p-2, 0x1.442847cb75d73p-58},
    {0x1.7f406p-1, 0x1.2895a0bde86a4p-2, -0x1.0a5b682d74d38p-57},
    {0x1.7d05f4p-1, 0x1.2e8e2bee11d31p-2, -0x1.0f4cdb90968a4p-56},
    {0x1.7ad22p-1, 0x1.347ddb2987d59p-2, 0x1.5915a1bfb7318p-56},
    {0x1.78a4c8p-1, 0x1.3a64c596945eap-2, -0x1.8d0ca31369da2p-58},
    {0x1.767dcep-1, 0x1.404309206a7e5p-2, -0x1.d39f6b12df22ep-57},
    {0x1.745d18p-1, 0x1.4618ba21c5ecap-2, 0x1.f42de234224b2p-56},
    {0x1.724288p-1, 0x1.4be5f937778a1p-2, -0x1.cb366b633ad24p-58},
    {0x1.702e06p-1, 0x1.51aad7c2df82ep-2, -0x1.0db0aebabfed6p-60},
    {0x1.6e1f76p-1, 0x1.5767736c55a74p-2, 0x1.51ab95537992p-58},
    {0x1.6c16c2p-1, 0x1.5d1bda55809dp-2, -0x1.9dc9cd7ae2aaep-56},
};
constexpr std::uint64_t kM0Bits = 0x3FE6900000000000;  // m0

/// log(x) = hi + lo for positive finite x: x = 2^e m, m c = 1 + r exactly, log(x) = e ln2 +
/// log(1/c) + log1p(r). Relative error below 2^-68 (the series' rounding where x is near 1; below
/// 2^-73 elsewhere)
DoubleDouble logOf(double x) {
  const bool subnormal = x < 0x1p-1022;
  const std::uint64_t bits = detail::bitsOf(subnormal ? x * 0x1p52 : x);  // (exactly scaled)
  // the bits from those of m0 on: the exponent e (+ 1024), then the interval in the next 7 bits
  const std::uint64_t offset = bits - kM0Bits + (1024ull << 52);
  const std::uint64_t exponentBits = (offset >> 52 << 52) - (1024ull << 52);  // e 2^52 (mod 2^64)
  const int e = static_cast<int>(offset >> 52) - 1024 - (subnormal ? 52 : 0);
  const LogEntry& entry = kLogTable[offset >> 45 & 127];
  const double m = detail::fromBits(bits - exponentBits);
  // r = m c - 1 exactly: m's top 26 bits and the other 27 times c (25 bits) are exact products,
  // and their first minus 1 is exact (Sterbenz)
  const double mHigh = detail::fromBits(detail::bitsOf(m) & ~0x7FFFFFFull);
  const DoubleDouble r = detail::twoSum(mHigh * entry.c - 1.0, (m - mHigh) * entry.c);
  // log1p(r) = r - r^2/2 + r^3 (1/3 - r/4 + ... + r^6/9) (the rest below 2^-75 r): the first two
  // terms in double-double, r.hi^2 from its 26-bit high part (squared exactly) and the rest
  const double z = r.hi, zHigh = detail::fromBits(detail::bitsOf(z) & ~0x7FFFFFFull), zLow = z - zHigh;
  const double squareHi = zHigh * zHigh, squareLo = (z + zHigh) * zLow + 2.0 * z * r.lo;
  const double z2 = z * z, z4 = z2 * z2;  // (Estrin's scheme: a short chain of dependent operations)
  const double series = z * z2 *
                        (((1.0 / 3 - 0.25 * z) + z2 * (0.2 - 1.0 / 6 * z)) +
                         z4 * ((1.0 / 7 - 0.125 * z) + z2 * (1.0 / 9)));
  const DoubleDouble lead = detail::fastTwoSum(z, -0.5 * squareHi);  // |r| <= 2^-8
  const double log1pTail = lead.lo + ((r.lo - 0.5 * squareLo) + series);
  // e ln2 + log(1/c) + log1p(r), each sum from the larger part (e ln2 is 0 or >= ln2, and
  // |log(1/c)| >= 2^-7.4 where c != 1)
  const double ed = e;
  const DoubleDouble tableSum = detail::fastTwoSum(ed * kLn2Hi, entry.logHi);  // ed kLn2Hi exact
  const DoubleDouble total = detail::fastTwoSum(tableSum.hi, lead.hi);
  const double tail = ((ed * kLn2Lo + entry.logLo) + tableSum.lo) + (total.lo + log1pTail);
  return detail::fastTwoSum(total.hi, tail);
}

/// pow(x, y) for finite x > 0, x != 1, finite y != 0
double powOfPositive(double x, double y) {
  // |log x| > 2^-54 for x != 1: beyond 2^63, |y log x| > 512 over- or underflows
  if (std::fabs(y) > 0x1p63) return (x < 1.0) == (y > 0.0) ? 0.0 : kInfinity;
  const DoubleDouble logX = logOf(x);
  const DoubleDouble product = detail::twoProduct(y, logX.hi);
  const DoubleDouble exponent = detail::fastTwoSum(product.hi, product.lo + y * logX.lo);
  if (exponent.hi > 709.8) return kInfinity;  // exp(709.8) > DBL_MAX
  if (exponent.hi < -745.2) return 0.0;       // exp(-745.2) < 2^-1075, the half of the least subnormal
  return expOfSum(exponent.hi, exponent.lo);
}

/// pow(+-0 or +-inf, y) for finite y != 0 (Annex F): 0 or inf, negative for a negative x and an odd y
double powOfZeroOrInfinity(double x, double y, bool oddY) {
  const double magnitude = (x == 0.0) == (y < 0.0) ? kInfinity : 0.0;
  return oddY && std::signbit(x) ? -magnitude : magnitude;
}

}  // namespace

double exp(double x) {
  if (std::isnan(x)) return x + x;
  if (x > 7.09782712893383973096e+02) return kInfinity;  // fdlibm's thresholds: the last finite result,
  if (x < -7.45133219101941108420e+02) return 0.0;       // the last that rounds to 2^-1074
  return expOfSum(x, 0.0);
}

double log(double x) {
  if (x > 0.0 && x < kInfinity) return logOf(x).hi;
  if (x == 0.0) return -kInfinity;
  if (x < 0.0) return std::numeric_limits<double>::quiet_NaN();
  return x + x;  // NaN, +inf
}

double pow(double x, double y) {
  if (y == 0.0 || x == 1.0) return 1.0;  // even for a NaN
  if (std::isnan(x) || std::isnan(y)) return x + y;
  if (y == 1.0) return x;  // exact cases, also for zeros and infinities
  if (y == 2.0) return x * x;
  if (y == -1.0) return 1.0 / x;
  if (std::isinf(y)) return std::fabs(x) == 1.0 ? 1.0 : (std::fabs(x) < 1.0) == (y > 0.0) ? 0.0 : kInfinity;
  const bool integerY = std::fabs(y) >= 0x1p52 || static_cast<double>(static_cast<long long>(y)) == y;
  const bool oddY = std::fabs(y) < 0x1p53 && integerY && (static_cast<long long>(y) & 1) != 0;
  if (x == 0.0 || std::isinf(x)) return powOfZeroOrInfinity(x, y, oddY);
  if (x > 0.0) return powOfPositive(x, y);
  if (!integerY) return std::numeric_limits<double>::quiet_NaN();  // a negative base, a fraction
  if (x == -1.0) return oddY ? -1.0 : 1.0;                         // (also for |y| beyond 2^63)
  return oddY ? -powOfPositive(-x, y) : powOfPositive(-x, y);
}

}  // namespace chaindrive::math

extern "C" double chaindrive_pow(double x, double y) { return chaindrive::math::pow(x, y); }
