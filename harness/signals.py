"""Input time series for runs: crankshaft speed with rotational vibration and camshaft load
torques from engine-order harmonics (a placeholder valve-train load until measured-torque tables
are used)."""
import math

import numpy as np

# Camshaft load torque per camshaft [N m]: mean drag plus engine-order harmonics (order per
# crankshaft revolution, amplitude, phase [rad]). A four-cylinder camshaft has four cam events
# per camshaft revolution, i.e. engine order 2 and its multiples (DOMAIN: mean 1-4 N m,
# alternating +-10-25 N m, orders 2, 4, 6, 8).
DEFAULT_CAM_TORQUE = {
    "camshaftIntake": (2.5, [(2, 12.0, 0.0), (4, 5.0, 0.6), (6, 2.0, 1.1), (8, 1.0, 1.9)]),
    "camshaftExhaust": (2.5, [(2, 11.0, 1.2), (4, 4.5, 2.0), (6, 1.8, 2.6), (8, 0.9, 0.4)]),
}


def crank_vibration_deg(rpm):
    """Order-2 rotational vibration amplitude [deg]: about 2.7 deg at 800 rpm idle, falling with
    1/n^2 (DOMAIN), not below 0.1 deg (torsional resonance region)."""
    return max(0.1, 2.7 * (800.0 / rpm) ** 2)


def write_inputs_csv(path, rpm, duration, dt=2e-5, cam_torque=DEFAULT_CAM_TORQUE, vibration_deg=None,
                     crank="crankshaft"):
    """Writes a time-series input CSV for chaindrive-run."""
    w0 = rpm * 2.0 * math.pi / 60.0
    a = math.radians(crank_vibration_deg(rpm) if vibration_deg is None else vibration_deg)
    t = np.arange(0.0, duration + dt, dt)
    theta = w0 * t
    cols = {crank + ".w": w0 + 2.0 * w0 * a * np.cos(2.0 * theta)}
    for name, (mean, orders) in cam_torque.items():
        tau = np.full_like(t, mean)
        for k, amp, ph in orders:
            tau += amp * np.sin(k * theta + ph)
        cols[name + ".tau"] = tau
    with open(path, "w") as f:
        f.write("# inputs for chaindrive-run: SI units (s, rad/s, N m)\n")
        f.write(f"# crankshaft {rpm:g} rpm with order-2 vibration of {math.degrees(a):.3f} deg; camshaft torques from "
                "engine-order harmonics (harness/signals.py)\n")
        f.write("time," + ",".join(cols) + "\n")
        data = np.column_stack([t] + list(cols.values()))
        np.savetxt(f, data, delimiter=",", fmt="%.10g")
    return path
