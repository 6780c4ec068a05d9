"""Physical model behind the SYNTHESIZED "measured" tables of harness/tables/data and
harness/tables/data_sport: the valve-train load torque of the two camshafts and the crankshaft
speed fluctuation of a four-cylinder four-stroke DOHC petrol engine. No measurement enters; every
parameter below is an engineering estimate ([E]) or derived from one ([D]), with its reasoning,
and harness/tables/data/README.md repeats them.

Each engine is one immutable `Engine`: firing order (and from it the firing TDCs), the intake
and exhaust `ValveTrain`s, the `CrankSpeedModel`, the cam/bucket friction law and the camshaft
drag law. Two are defined (ENGINES):
* "i4-bucket" (I4_BUCKET, the default; tables in harness/tables/data): the engine described
  below;
* "i4-sport" (I4_SPORT; tables in harness/tables/data_sport): the same layout with another
  engine's cams, springs, phasing and crank train, see "Engine i4-sport" at the end.
The module-level INTAKE, EXHAUST, CAMSHAFTS, CRANK, FIRING_ORDER and FIRING_TDC_DEG are those of
the default engine.

SI units inside (m, N, kg, s, rad); angles given in degrees carry the suffix _deg. The public
functions take the crank angle theta in degrees from cylinder 1 firing TDC, as the tables do.

Engine
------
Four cylinders, firing order 1-3-4-2: firing TDC of cylinder 1, 3, 4, 2 at theta = 0, 180, 360,
540 deg. Camshafts turn at half crankshaft speed: camshaft angle phi = theta / 2.
Valve events (crank angle, at the ends of the cam's main event, i.e. the ramp ends; the valve
itself leaves its seat on the opening ramp, see CamLobe.valve_open_deg):

    intake  opens 10 deg BTDC of gas exchange (350 deg after firing TDC), closes 50 deg ABDC (590)
    exhaust opens 50 deg BBDC (130 deg after firing TDC),                  closes 10 deg ATDC (370)

so the lobe centres (maximum lift) lie at 470 deg (intake, 110 deg after gas-exchange TDC) and
250 deg (exhaust, 110 deg before it) after the cylinder's firing TDC, both typical centre lines.

Cam lift law (per lobe, symmetric about its centre; phi_c = cam angle from the lobe centre)
--------------------------------------------------------------------------------------------
Cam lift h_c = tappet lift, valve lift h_v = max(0, h_c - lash).
* Main event, |phi_c| <= T (T = half the main duration in cam angle), a polydyne of the
  2-12-14-16 family:  h_c = H (1 + C2 x^2 + C12 x^12 + C14 x^14 + C16 x^16),  x = phi_c / T,
  H = valve lift + lash (the total cam lift); the four C are solved so that at x = +-1 the lift
  equals the ramp height, the slope equals the ramp velocity and acceleration and jerk vanish
  (the lift is C3 there). It has a short, high positive acceleration on the flanks and a broad,
  lower negative acceleration over the nose, as cams for flat followers do.
* Ramps, T < |phi_c| <= T + L: a constant-velocity ramp of height H_r (the "clearance ramp"
  that takes up the lash at a controlled seating speed) whose velocity builds up smoothly
  (cubic smoothstep) over the first L_a of its length L:  v(s) = v_r S(s / L_a),
  S(u) = 3u^2 - 2u^3 (u < 1), s = distance from the ramp start; v_r = H_r / (L - L_a / 2).
* Base circle elsewhere: h_c = 0.

Contact force and torque per valve (direct-acting bucket tappet, flat face)
---------------------------------------------------------------------------
With the lash open (h_c <= lash) cam and tappet do not touch: F = 0. Otherwise

    F   = F_0 + k h_v + m_eff h_tt                         (spring preload and rate, inertia)
    h_tt = h_phiphi omega_c^2 + h_phi alpha_c              (valve acceleration at the actual,
                                                            fluctuating camshaft speed)
    tau = F h_phi + mu F (r_b + h_c)                       (torque opposing the camshaft)

h_phi = dh_c/dphi is the offset of the contact point from the tappet axis for a flat follower,
so F h_phi is the exact torque of the normal force; the friction force mu F acts along the
tappet face at the distance r_b + h_c from the cam axis and always opposes the rotation (the
cam's radius of curvature r_b + h_c + h_phiphi stays positive, see CamLobe.min_curvature_radius).
F < 0 would mean that the valve train separates from the cam (valve float / jump): it is
clamped at 0 and counted (CamshaftLoad.separated); with the parameters below it does not occur
below about 9400 rpm (float_speed; at 6000 rpm the contact force beyond 0.5 mm lift stays above
250 N).
omega_c = omega / 2 and alpha_c = (1/2) omega d omega / d theta come from the crankshaft speed
model below (rigid chain); the camshaft's own inertia is not part of the load (the chain
solver's camshaft sprocket carries it).

Per camshaft: two valves per cylinder, four cylinders, plus the mean bearing/seal drag
    tau_drag(n) = 1.0 N m + 0.12 N m per 1000 rpm
(five plain journal bearings and a front seal: boundary and seal friction plus a viscous part).

Crankshaft speed (absolute speed at the crankshaft sprocket)
-----------------------------------------------------------
theta_true = theta + delta(theta); the speed omega = omega_0 (1 + d delta / d theta), whose mean
over the crank angle is omega_0 = 2 pi n / 60 exactly. The gas-torque harmonics of an
in-line four (engine orders k = 2, 4, 6, ..., 40) are modelled as T_k cos(k (theta - theta_p))
with T_k / T_2 = 2 / k (a short pressure pulse per firing) and the pulse centre theta_p = 50 deg
after each firing TDC (with the higher orders the speed is lowest about 15-20 deg and
highest about 75-80 deg after each firing TDC). They turn
* the rigid crank train (flywheel, crankshaft, inertia J): angle amplitude A_k = T_k / (J k^2
  omega_0^2), in phase opposition to the torque; calibrated to A_2 = 2.7 deg at 800 rpm idle
  (the published idle swing of about 710-860 rpm), hence A_2(n) = 2.7 deg (800 rpm / n)^2 and
  A_k = A_2 (2 / k)^3 (T_2 / J = 1323 rad/s^2, e.g. T_2 = 200 N m on J = 0.15 kg m^2);
* at the crank nose, where the sprocket sits, the first torsional mode of the crankshaft
  (crank nose and pulley against the flywheel; natural frequency f_r = 400 Hz, damping ratio
  zeta = 0.03) multiplies this by H(r) = 1 / (1 - r^2 + 2 i zeta r), r = k n / 60 / f_r: for two
  inertias J_1 (front) and J_2 (flywheel) coupled by the crank's torsional stiffness, with the
  torque on J_2, the angle of J_1 is exactly the rigid-body angle times 1 / (1 - r^2) (plus
  damping). H is 1.33 for order 2 at 6000 rpm and about 1 / (2 zeta) = 17 at resonance: 0.10 deg
  at order 4 at 6000 rpm, 0.07 deg at order 6 at 4000 rpm, 0.05 deg at order 8 at 3000 rpm,
  0.03 deg at order 12 at 2000 rpm.
In complex form: delta(theta) = sum_k Re{-A_k H(r_k) exp(i k (theta - theta_p))}.
A slight cylinder-to-cylinder imbalance adds orders 0.5, 1 and 1.5 with angle amplitudes
0.08, 0.02 and 0.009 A_2 (a torque imbalance of 0.5 % of T_2) at fixed phases.

Engine i4-sport
---------------
Another four-cylinder four-stroke DOHC engine with bucket tappets, firing order 1-3-4-2 (the
solver's cycle statistics look at engine orders 2, 4, 6, 8), same laws as above; what differs
(all [E]):
* cams: valve lift 10.0 mm intake, 9.5 mm exhaust; main duration 260 / 252 deg crank (lash,
  ramps and the polydyne family as i4-bucket);
* phasing: the intake cam phaser holds the intake lobe centre 100 deg after gas-exchange TDC
  (460 deg after firing TDC; intake main event 330-590), the exhaust lobe centre lies 105 deg
  before it (255; exhaust main event 129-381): 10 deg earlier / 5 deg later than i4-bucket;
* valve springs 280 N preload, 52 N/mm (800 N at full intake lift); effective moving masses
  95 g intake, 88 g exhaust;
* bucket 35 mm (tappet radius 17.5 mm): the largest contact offset is 15.7 mm, which a 33 mm
  bucket would hold with only 0.8 mm to its edge, less than its edge chamfer (about 1 mm);
* DLC-coated buckets: mu = 0.04 + 0.02 (1000 rpm / n); bearing and seal drag 0.8 N m + 0.10 N m
  per 1000 rpm per camshaft;
* crank train: order-2 angle amplitude 3.2 deg at 800 rpm (lighter flywheel), first torsional
  mode at 330 Hz with damping ratio 0.04 (order 4 resonant at 4950 rpm, order 6 at 3300 rpm,
  order 8 at 2475 rpm); gas-torque harmonics and imbalance as i4-bucket.
Checks (tests/python/tables/test_tables.py): the cams stay convex for the flat follower
(smallest radius of curvature 4.1 mm intake, 3.4 mm exhaust), no valve float at 1000-6000 rpm
(contact force first zero at about 10300 rpm intake, 10400 rpm exhaust).

High-pressure fuel pump (HighPressurePump, HP_PUMP; the test drive diesel_pump's hpPump)
----------------------------------------------------------------------------------------
A single-plunger common-rail pump with a two-lobe cam on its own shaft (CP4.1 type), over the
pump's own angle psi [deg]. Each lobe lifts the plunger l = (h / 2)(1 - cos(2 (psi - psi_0)))
(psi_0: where lobe 1's delivery stroke starts); on the rising flank (half of each 180-deg lobe)
the plunger works against the rail pressure p, force p A, and the torque is p A dl/dpsi, a
half-sine pulse; on the falling flank (filling, low pressure) it is 0. With the hydro-mechanical
efficiency eta and the displacement V_g = 2 A h per revolution:

    tau(psi) = tau_drag + tau_peak max(0, sin(2 (psi - psi_0))),  tau_peak = pi V_g p / (2 pi eta)

so the mean is tau_drag + V_g p / (2 pi eta) [physics] and the peak pi times the hydraulic
mean; two pulses of 90 deg per pump revolution (LAYOUTS.md section 3). Full delivery is
assumed at every speed (the chain's worst case; metering at part load shortens the stroke); the
plunger return spring (+- about its mean zero) and the pressure build-up before delivery are
left out. Estimates [E]: V_g = 0.25 cm^3 per revolution (LAYOUTS: 0.25-0.5), eta = 0.85, rail
pressure 1000 bar at 1000 rpm rising 300 bar per 1000 rpm to at most 1800 bar (from 3667 rpm),
drag 0.3 N m (two plain bearings and a shaft seal): mean 4.98, 7.79, 8.73 N m and pulse peak
above the drag 14.7, 23.5, 26.5 N m at 1000, 3000, 6000 rpm.
"""
import math
from dataclasses import dataclass

import numpy as np

DEG = math.pi / 180.0


def _smoothstep_velocity(s, v_r, l_a):
    """Ramp velocity build-up: lift, slope and acceleration of v(s) = v_r S(s / l_a) integrated,
    S(u) = 3u^2 - 2u^3, constant v_r beyond l_a; s >= 0 in cam rad."""
    u = np.clip(s / l_a, 0.0, 1.0)
    h_in = v_r * l_a * (u ** 3 - 0.5 * u ** 4)
    h = np.where(s < l_a, h_in, v_r * (0.5 * l_a + (s - l_a)))
    v = np.where(s < l_a, v_r * (3 * u ** 2 - 2 * u ** 3), v_r)
    a = np.where(s < l_a, v_r * 6.0 * u * (1.0 - u) / l_a, 0.0)
    return h, v, a


@dataclass(frozen=True)
class CamLobe:
    """One cam lobe (see the module text for the law). Lengths in m, durations in crank deg."""
    valve_lift: float = 8.5e-3          # [E] maximum valve lift, 8-9 mm for a 4-valve petrol engine
    lash: float = 0.20e-3               # [E] cold valve clearance of a mechanical bucket tappet
    main_duration_deg: float = 240.0    # [E] ramp end to ramp end (brief: 240-250 deg)
    ramp_height: float = 0.30e-3        # [E] clearance ramp, a little above the lash
    ramp_length_deg: float = 40.0       # [E] 20 deg cam per ramp
    ramp_onset_deg: float = 16.0        # [E] ramp velocity builds up over 8 deg cam
    exponents: tuple = (2, 12, 14, 16)  # [E] polydyne family (C3 at the ramp ends)

    @property
    def total_lift(self):
        return self.valve_lift + self.lash

    @property
    def half_main(self):
        """T: half the main event [cam rad]."""
        return 0.25 * self.main_duration_deg * DEG

    @property
    def ramp_length(self):
        return 0.5 * self.ramp_length_deg * DEG

    @property
    def ramp_onset(self):
        return 0.5 * self.ramp_onset_deg * DEG

    @property
    def ramp_velocity(self):
        """v_r = dh/dphi on the constant-velocity part of the ramp [m/rad]."""
        return self.ramp_height / (self.ramp_length - 0.5 * self.ramp_onset)

    @property
    def coefficients(self):
        """C_e of the polydyne, from lift, slope, acceleration and jerk at x = 1."""
        H, T = self.total_lift, self.half_main
        target = [self.ramp_height / H - 1.0, -self.ramp_velocity * T / H, 0.0, 0.0]
        A = [[math.prod(e - i for i in range(d)) for e in self.exponents] for d in range(4)]
        return np.linalg.solve(np.array(A, float), np.array(target))

    def lift(self, phi):
        """Cam lift h_c [m] and its derivatives d/dphi [m/rad], d2/dphi2 [m/rad^2] at the cam
        angle phi [rad] from the lobe centre (any real value; one lobe, no periodic wrap)."""
        phi = np.asarray(phi, float)
        u = np.abs(phi)
        sgn = np.where(phi < 0.0, -1.0, 1.0)
        H, T, L = self.total_lift, self.half_main, self.ramp_length
        x = np.minimum(u / T, 1.0)
        h_m = np.full_like(x, H)
        d_m = np.zeros_like(x)
        a_m = np.zeros_like(x)
        for c, e in zip(self.coefficients, self.exponents):
            h_m += H * c * x ** e
            d_m += H * c * e * x ** (e - 1) / T
            a_m += H * c * e * (e - 1) * x ** (e - 2) / T ** 2
        s = np.clip(T + L - u, 0.0, L)  # distance from the ramp start, towards the lobe centre
        h_r, v_r, a_r = _smoothstep_velocity(s, self.ramp_velocity, self.ramp_onset)
        main = u <= T
        ramp = (u > T) & (u < T + L)
        h = np.where(main, h_m, np.where(ramp, h_r, 0.0))
        d = np.where(main, d_m, np.where(ramp, -v_r, 0.0)) * sgn
        a = np.where(main, a_m, np.where(ramp, a_r, 0.0))
        return h, d, a

    @property
    def valve_open_deg(self):
        """Crank degrees by which the valve leaves its seat before the main event starts (and
        returns after it ends): the part of the ramp above the lash."""
        return 2.0 * (self.ramp_height - self.lash) / self.ramp_velocity / DEG

    def min_curvature_radius(self, base_radius):
        """Smallest radius of curvature r_b + h + h'' of the cam for a flat follower [m]."""
        phi = np.linspace(0.0, self.half_main + self.ramp_length, 4001)
        h, _, a = self.lift(phi)
        return float(np.min(base_radius + h + a))


@dataclass(frozen=True)
class ValveTrain:
    """The valves of one camshaft: lobe, spring, masses, friction, timing."""
    name: str
    lobe: CamLobe
    centre_after_firing_tdc_deg: float  # lobe centre (max lift), crank deg after the cylinder's firing TDC
    effective_mass: float               # [kg] valve + retainer/keepers + bucket/shim + 1/3 spring
    spring_preload: float = 220.0       # [E] N, installed (valve closed); brief 200-250 N
    spring_rate: float = 38.0e3         # [E] N/m (38 N/mm; brief 30-45), 543 N at 8.5 mm
    base_radius: float = 20.0e-3        # [E] cam base circle radius (40 mm diameter)
    tappet_radius: float = 16.5e-3      # [E] bucket of 33 mm: must exceed the largest offset h_phi
    valves_per_cylinder: int = 2


@dataclass(frozen=True)
class FrictionLaw:
    """Cam/bucket friction coefficient [-], mixed lubrication falling with speed (Stribeck):
    mu(n) = base + low_speed (1000 rpm / n)."""
    base: float
    low_speed: float

    def __call__(self, rpm):
        return self.base + self.low_speed * 1000.0 / rpm


@dataclass(frozen=True)
class DragLaw:
    """Mean camshaft bearing and seal drag per camshaft [N m]: base + per_1000rpm (n / 1000 rpm)."""
    base: float
    per_1000rpm: float

    def __call__(self, rpm):
        return self.base + self.per_1000rpm * rpm / 1000.0


@dataclass
class CamshaftLoad:
    """Load torque of one camshaft over the crank angle and its parts [N m]."""
    theta_deg: np.ndarray
    total: np.ndarray
    spring: np.ndarray        # sum of F_spring h_phi
    inertia: np.ndarray       # sum of m_eff h_tt h_phi
    friction: np.ndarray      # sum of mu F (r_b + h_c)
    drag: float
    min_contact_force: float  # smallest contact force while the lash is closed [N]
    separated: int            # samples with clamped (negative) contact force, summed over valves
    max_offset: float         # largest |h_phi| [m] (contact point offset on the bucket)


@dataclass(frozen=True)
class CrankSpeedModel:
    """Parameters of the crankshaft speed fluctuation (see the module text)."""
    idle_rpm: float = 800.0
    idle_amplitude_deg: float = 2.7        # [P]/[D] order-2 angle amplitude at idle (710-860 rpm swing)
    pulse_centre_deg: float = 50.0         # [E] theta_p: gas-torque pulse centre after firing TDC
    max_order: int = 40                    # firing orders base_order, 2 base_order, ... up to 40
    base_order: int = 2                    # the firing order: cylinders / 2 of a four-stroke (I4: 2, V6: 3)
    resonance_hz: float = 400.0            # [E] first crank torsional mode (300-500 Hz)
    resonance_damping: float = 0.03        # [E] damping ratio (crank with rubber damper, 0.02-0.05)
    # [E] cylinder imbalance: (order, angle amplitude relative to A_2, phase [deg])
    imbalance: tuple = ((0.5, 0.08, 30.0), (1.0, 0.02, 120.0), (1.5, 0.009, 250.0))

    def order2_amplitude_deg(self, rpm):
        """Rigid-body angle amplitude A_2(n) [deg] of the firing order (base_order: order 2 of an I4)."""
        return self.idle_amplitude_deg * (self.idle_rpm / rpm) ** 2

    def amplification(self, order, rpm):
        """H(r) of the first torsional mode at the crank nose for an engine order."""
        r = order * rpm / 60.0 / self.resonance_hz
        return 1.0 / (1.0 - r * r + 2j * self.resonance_damping * r)

    def harmonics(self, rpm):
        """Complex angle amplitudes [rad] per engine order: delta = sum Re{c_k exp(i k theta)}."""
        a2 = self.order2_amplitude_deg(rpm) * DEG
        out = {}
        b = self.base_order
        for k in range(b, self.max_order + 1, b):
            out[float(k)] = -a2 * (float(b) / k) ** 3 * self.amplification(k, rpm) \
                * np.exp(-1j * k * self.pulse_centre_deg * DEG)
        for k, rel, ph in self.imbalance:
            out[float(k)] = rel * a2 * self.amplification(k, rpm) * np.exp(1j * ph * DEG)
        return out

    def speed(self, theta_deg, rpm, scale=1.0):
        """Crankshaft speed omega [rad/s] and d omega / d theta [rad/s per rad] at theta [deg];
        `scale` multiplies the fluctuation (cycle-to-cycle variation)."""
        th = np.asarray(theta_deg, float) * DEG
        w0 = rpm * 2.0 * math.pi / 60.0
        d1 = np.zeros_like(th)
        d2 = np.zeros_like(th)
        for k, c in self.harmonics(rpm).items():
            e = np.exp(1j * k * th)
            d1 += np.real(1j * k * c * e)
            d2 += np.real(-(k * k) * c * e)
        return w0 * (1.0 + scale * d1), w0 * scale * d2


@dataclass(frozen=True)
class Engine:
    """Everything the tables of one engine depend on (see the module text)."""
    name: str                          # the --engine choice
    description: str                   # the layout, one line (the tables' `engine:` header line)
    intake: ValveTrain
    exhaust: ValveTrain
    crank: CrankSpeedModel
    friction: FrictionLaw              # cam/bucket friction coefficient mu(n)
    drag: DragLaw                      # bearing and seal drag per camshaft [N m]
    firing_order: tuple = (1, 3, 4, 2)

    def __post_init__(self):
        if sorted(self.firing_order) != list(range(1, len(self.firing_order) + 1)):
            raise ValueError(f"engine {self.name}: firing order {self.firing_order} is not a permutation of the cylinders")

    @property
    def firing_tdc_deg(self):
        """Firing TDC of each cylinder [deg crank after cylinder 1 firing TDC], evenly spaced over
        the 720-deg cycle in the firing order."""
        step = 720.0 / len(self.firing_order)
        return {cyl: step * i for i, cyl in enumerate(self.firing_order)}

    @property
    def camshafts(self):
        return (self.intake, self.exhaust)


I4_BUCKET = Engine(
    name="i4-bucket",
    description="4-cylinder 4-stroke DOHC, firing order 1-3-4-2, 2 intake + 2 exhaust valves per cylinder, "
                "bucket tappets",
    intake=ValveTrain(
        name="camshaftIntake",
        lobe=CamLobe(valve_lift=8.5e-3, lash=0.20e-3),
        centre_after_firing_tdc_deg=470.0,
        # [E] valve 40 g (about 33 mm head) + bucket with shim 22 g + retainer and keepers 6 g
        # + one third of a 36 g spring 12 g
        effective_mass=0.080,
    ),
    exhaust=ValveTrain(
        name="camshaftExhaust",
        lobe=CamLobe(valve_lift=8.0e-3, lash=0.25e-3),  # [E] smaller exhaust valves, larger (hot) lash
        centre_after_firing_tdc_deg=250.0,
        effective_mass=0.075,                            # [E] valve 35 g, the rest as intake
    ),
    crank=CrankSpeedModel(),
    # [E] mixed lubrication: 0.09 at 1000 rpm, 0.065 at 6000 rpm
    friction=FrictionLaw(base=0.06, low_speed=0.03),
    # [E] five plain journal bearings and a front seal: 1.0 N m + 0.12 N m per 1000 rpm
    drag=DragLaw(base=1.0, per_1000rpm=0.12),
)

I4_SPORT = Engine(
    name="i4-sport",
    description="4-cylinder 4-stroke DOHC, firing order 1-3-4-2, 2 intake + 2 exhaust valves per cylinder, "
                "DLC-coated bucket tappets, intake cam phaser",
    intake=ValveTrain(
        name="camshaftIntake",
        # [E] higher lift and a longer main event (260 deg crank); lash and ramps as i4-bucket
        lobe=CamLobe(valve_lift=10.0e-3, lash=0.20e-3, main_duration_deg=260.0),
        # [E] cam phaser position: lobe centre 100 deg after gas-exchange TDC (360 + 100)
        centre_after_firing_tdc_deg=460.0,
        # [E] valve 46 g (about 35 mm head) + bucket with shim 24 g + retainer and keepers 7 g
        # + one third of a 54 g spring 18 g
        effective_mass=0.095,
        spring_preload=280.0,          # [E] N, installed
        spring_rate=52.0e3,            # [E] N/m (52 N/mm), 800 N at 10.0 mm
        # [E] bucket of 35 mm: the largest contact offset is 15.7 mm, so a 33 mm bucket (16.5 mm)
        # would keep the contact only 0.8 mm from its edge, inside the edge chamfer (about 1 mm)
        tappet_radius=17.5e-3,
    ),
    exhaust=ValveTrain(
        name="camshaftExhaust",
        # [E] 9.5 mm lift, 252 deg crank main event, larger (hot) lash
        lobe=CamLobe(valve_lift=9.5e-3, lash=0.25e-3, main_duration_deg=252.0),
        # [E] lobe centre 105 deg before gas-exchange TDC (360 - 105)
        centre_after_firing_tdc_deg=255.0,
        effective_mass=0.088,          # [E] valve 39 g, the rest as intake
        spring_preload=280.0,          # [E] N, same springs as intake
        spring_rate=52.0e3,            # [E] N/m, 774 N at 9.5 mm
        tappet_radius=17.5e-3,         # [E] 35 mm, as intake (largest offset 15.4 mm)
    ),
    crank=CrankSpeedModel(
        idle_amplitude_deg=3.2,        # [E] order-2 angle amplitude at 800 rpm (lighter flywheel)
        resonance_hz=330.0,            # [E] first crank torsional mode, low in the 300-500 Hz range
        resonance_damping=0.04,        # [E] damping ratio (crank with a viscous-rubber damper)
    ),
    # [E] DLC-coated buckets: 0.06 at 1000 rpm, 0.043 at 6000 rpm
    friction=FrictionLaw(base=0.04, low_speed=0.02),
    # [E] plain journal bearings and a low-friction front seal: 0.8 N m + 0.10 N m per 1000 rpm
    drag=DragLaw(base=0.8, per_1000rpm=0.10),
)

ENGINES = {e.name: e for e in (I4_BUCKET, I4_SPORT)}
DEFAULT_ENGINE = I4_BUCKET

# the default engine's parts
FIRING_ORDER = I4_BUCKET.firing_order
FIRING_TDC_DEG = I4_BUCKET.firing_tdc_deg   # [deg crank after cylinder 1 firing TDC]
INTAKE = I4_BUCKET.intake
EXHAUST = I4_BUCKET.exhaust
CAMSHAFTS = I4_BUCKET.camshafts
CRANK = I4_BUCKET.crank


def camshaft_load(train, theta_deg, rpm, engine=DEFAULT_ENGINE, crank_scale=1.0):
    """Load torque of one camshaft (a ValveTrain of `engine`) over theta [deg crank from
    cylinder 1 firing TDC] at the engine speed rpm, with the valve inertia at the engine's crank
    model's fluctuating speed (its fluctuation times crank_scale)."""
    theta_deg = np.asarray(theta_deg, float)
    omega, domega = engine.crank.speed(theta_deg, rpm, crank_scale)
    w_c = 0.5 * omega
    alpha_c = 0.5 * omega * domega
    lobe = train.lobe
    mu = engine.friction(rpm)
    spring = np.zeros_like(theta_deg)
    inertia = np.zeros_like(theta_deg)
    friction = np.zeros_like(theta_deg)
    fmin, separated, offset = math.inf, 0, 0.0
    for cyl, tdc in engine.firing_tdc_deg.items():
        centre = tdc + train.centre_after_firing_tdc_deg
        rel = (theta_deg - centre + 360.0) % 720.0 - 360.0   # crank deg from the lobe centre
        h, h1, h2 = lobe.lift(0.5 * rel * DEG)
        contact = h > lobe.lash
        hv = np.maximum(h - lobe.lash, 0.0)
        f_spring = train.spring_preload + train.spring_rate * hv
        f_inertia = train.effective_mass * (h2 * w_c ** 2 + h1 * alpha_c)
        f = f_spring + f_inertia
        if np.any(contact):
            fmin = min(fmin, float(np.min(f[contact])))
        separated += int(np.count_nonzero(contact & (f < 0.0)))
        scale = np.where(contact & (f > 0.0), 1.0, 0.0)   # lash open or separated: no force
        f_spring_c = np.where(f > 0.0, f_spring, 0.0) * scale
        f_inertia_c = np.where(f > 0.0, f_inertia, 0.0) * scale
        n = train.valves_per_cylinder
        spring += n * f_spring_c * h1
        inertia += n * f_inertia_c * h1
        friction += n * mu * (f_spring_c + f_inertia_c) * (train.base_radius + h)
        offset = max(offset, float(np.max(np.abs(h1))))
    drag = engine.drag(rpm)
    return CamshaftLoad(theta_deg, spring + inertia + friction + drag, spring, inertia, friction, drag,
                        fmin, separated, offset)


def float_speed(train, engine=DEFAULT_ENGINE, lo=1000.0, hi=20000.0):
    """Lowest engine speed [rpm] at which the contact force of `train` (a ValveTrain of
    `engine`) reaches zero (bisection on a 0.25 deg grid, with the engine's crank fluctuation)."""
    theta = np.arange(0.0, 720.0, 0.25)
    if camshaft_load(train, theta, hi, engine).min_contact_force > 0.0:
        return math.inf
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        if camshaft_load(train, theta, mid, engine).min_contact_force > 0.0:
            lo = mid
        else:
            hi = mid
    return hi


@dataclass(frozen=True)
class HighPressurePump:
    """The load torque of a single-plunger high-pressure pump with `lobes` cam lobes over its own
    angle (see "High-pressure fuel pump" in the module text). All parameters [E]."""
    lobes: int = 2
    displacement: float = 0.25e-6       # [E] V_g, m^3 per pump revolution (0.25 cm^3)
    efficiency: float = 0.85            # [E] hydro-mechanical efficiency eta
    rail_pressure_1000rpm: float = 1000e5   # [E] Pa, full load at 1000 rpm
    rail_pressure_per_1000rpm: float = 300e5  # [E] Pa per 1000 rpm above 1000 rpm
    rail_pressure_max: float = 1800e5   # [E] Pa, the system's limit
    drag: float = 0.3                   # [E] N m, bearings and shaft seal
    delivery_start_deg: float = 0.0     # psi_0: pump angle where lobe 1's delivery stroke starts

    def rail_pressure(self, rpm):
        """[Pa] at the engine speed rpm."""
        return min(self.rail_pressure_max,
                   self.rail_pressure_1000rpm + self.rail_pressure_per_1000rpm * (rpm - 1000.0) / 1000.0)

    def hydraulic_mean(self, rpm):
        """[N m] V_g p / (2 pi eta): the mean torque of the delivery without the drag."""
        return self.displacement * self.rail_pressure(rpm) / (2.0 * math.pi * self.efficiency)

    def peak(self, rpm):
        """[N m] the pulse's height above the drag: pi times the hydraulic mean."""
        return math.pi * self.hydraulic_mean(rpm)

    def mean(self, rpm):
        """[N m] the mean load torque over a revolution."""
        return self.drag + self.hydraulic_mean(rpm)

    def torque(self, psi_deg, rpm, delivery_scale=1.0):
        """Load torque [N m, opposing the rotation] at the pump angle psi [deg] (array); the
        pulses scaled by delivery_scale (cycle-to-cycle variation of the delivery)."""
        x = self.lobes * (np.asarray(psi_deg, float) - self.delivery_start_deg) * DEG
        return self.drag + delivery_scale * self.peak(rpm) * np.maximum(0.0, np.sin(x))


HP_PUMP = HighPressurePump()
