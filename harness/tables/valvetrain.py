"""Physical model behind the SYNTHESIZED "measured" tables of harness/tables/data: the valve-train
load torque of the two camshafts and the crankshaft speed fluctuation of a four-cylinder
four-stroke DOHC petrol engine. No measurement enters; every parameter below is an engineering
estimate ([E]) or derived from one ([D]), with its reasoning, and harness/tables/data/README.md
repeats them.

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
"""
import math
from dataclasses import dataclass, field

import numpy as np

DEG = math.pi / 180.0
FIRING_ORDER = (1, 3, 4, 2)
# firing TDC of each cylinder [deg crank after cylinder 1 firing TDC]
FIRING_TDC_DEG = {cyl: 180.0 * i for i, cyl in enumerate(FIRING_ORDER)}


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

    def friction_coefficient(self, rpm):
        """Cam/bucket friction [-]: mixed lubrication, falling with speed (Stribeck):
        mu = 0.06 + 0.03 (1000 rpm / n); 0.09 at 1000 rpm, 0.065 at 6000 rpm [E]."""
        return 0.06 + 0.03 * 1000.0 / rpm


INTAKE = ValveTrain(
    name="camshaftIntake",
    lobe=CamLobe(valve_lift=8.5e-3, lash=0.20e-3),
    centre_after_firing_tdc_deg=470.0,
    # [E] valve 40 g (about 33 mm head) + bucket with shim 22 g + retainer and keepers 6 g
    # + one third of a 36 g spring 12 g
    effective_mass=0.080,
)
EXHAUST = ValveTrain(
    name="camshaftExhaust",
    lobe=CamLobe(valve_lift=8.0e-3, lash=0.25e-3),  # [E] smaller exhaust valves, larger (hot) lash
    centre_after_firing_tdc_deg=250.0,
    effective_mass=0.075,                            # [E] valve 35 g, the rest as intake
)
CAMSHAFTS = (INTAKE, EXHAUST)


def drag_torque(rpm):
    """Mean camshaft bearing and seal drag per camshaft [N m]: 1.0 + 0.12 per 1000 rpm [E]."""
    return 1.0 + 0.12 * rpm / 1000.0


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
    max_order: int = 40                    # even orders 2..40
    resonance_hz: float = 400.0            # [E] first crank torsional mode (300-500 Hz)
    resonance_damping: float = 0.03        # [E] damping ratio (crank with rubber damper, 0.02-0.05)
    # cylinder imbalance: order -> (angle amplitude relative to A_2, phase [deg])
    imbalance: dict = field(default_factory=lambda: {0.5: (0.08, 30.0), 1.0: (0.02, 120.0), 1.5: (0.009, 250.0)})

    def order2_amplitude_deg(self, rpm):
        """Rigid-body order-2 angle amplitude A_2(n) [deg]."""
        return self.idle_amplitude_deg * (self.idle_rpm / rpm) ** 2

    def amplification(self, order, rpm):
        """H(r) of the first torsional mode at the crank nose for an engine order."""
        r = order * rpm / 60.0 / self.resonance_hz
        return 1.0 / (1.0 - r * r + 2j * self.resonance_damping * r)

    def harmonics(self, rpm):
        """Complex angle amplitudes [rad] per engine order: delta = sum Re{c_k exp(i k theta)}."""
        a2 = self.order2_amplitude_deg(rpm) * DEG
        out = {}
        for k in range(2, self.max_order + 1, 2):
            out[float(k)] = -a2 * (2.0 / k) ** 3 * self.amplification(k, rpm) \
                * np.exp(-1j * k * self.pulse_centre_deg * DEG)
        for k, (rel, ph) in self.imbalance.items():
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


CRANK = CrankSpeedModel()


def camshaft_load(train, theta_deg, rpm, crank=CRANK, crank_scale=1.0):
    """Load torque of one camshaft over theta [deg crank from cylinder 1 firing TDC] at the
    engine speed rpm, with the valve inertia at the crank model's fluctuating speed."""
    theta_deg = np.asarray(theta_deg, float)
    omega, domega = crank.speed(theta_deg, rpm, crank_scale)
    w_c = 0.5 * omega
    alpha_c = 0.5 * omega * domega
    lobe = train.lobe
    mu = train.friction_coefficient(rpm)
    spring = np.zeros_like(theta_deg)
    inertia = np.zeros_like(theta_deg)
    friction = np.zeros_like(theta_deg)
    fmin, separated, offset = math.inf, 0, 0.0
    for cyl, tdc in FIRING_TDC_DEG.items():
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
    drag = drag_torque(rpm)
    return CamshaftLoad(theta_deg, spring + inertia + friction + drag, spring, inertia, friction, drag,
                        fmin, separated, offset)


def float_speed(train, crank=CRANK, lo=1000.0, hi=20000.0):
    """Lowest engine speed [rpm] at which the contact force of `train` reaches zero (bisection
    on a 0.25 deg grid, with the crank model's fluctuation)."""
    theta = np.arange(0.0, 720.0, 0.25)
    if camshaft_load(train, theta, hi, crank).min_contact_force > 0.0:
        return math.inf
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        if camshaft_load(train, theta, mid, crank).min_contact_force > 0.0:
            lo = mid
        else:
            hi = mid
    return hi
