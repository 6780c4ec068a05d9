"""The damping values of the drive (and the raised ones of the study) in the measures of the
literature: damping ratios and restitution coefficients, with what the published sources give."""
import math

from ...drive.description import geometry
from ..methods import default_drive_json

ROLLER_SPEEDS = (1.0, 2.0, 3.0, 5.0)   # [m/s] roller seating impacts: about omega p
GUIDE_SPEEDS = (0.1, 0.3, 1.0, 3.0)    # [m/s] normal speeds of link plates meeting a guide
STEEL_DENSITY = 7800.0            # [kg/m^3]
OIL_VISCOSITY = (0.0085, 0.05)    # [Pa s] engine oil SAE 5W-30 hot (100 C) and warm (40 C) [E]


def hunt_crossley_restitution(alpha, speed):
    """Coefficient of restitution of one impact under the project's law F = k d (1 + 1.5 alpha d'),
    clamped at zero, at approach speed `speed` [m/s]. With exponent 1 it depends on alpha v only:
    in units of v/omega and 1/omega the penetration obeys u'' = -u max(0, 1 + 1.5 alpha v u')."""
    from scipy.integrate import solve_ivp
    a = 1.5 * alpha * speed

    def rhs(_, y):
        return [y[1], -y[0] * max(0.0, 1.0 + a * y[1])]

    def separated(_, y):
        return y[0]
    separated.terminal, separated.direction = True, -1.0
    sol = solve_ivp(rhs, (0.0, 100.0), [0.0, 1.0], events=separated, rtol=1e-10, atol=1e-12, max_step=0.01)
    return float(-sol.y_events[0][0][1])


def strand_lengths(geometry):
    """Lengths of the chain between two sprocket wraps (free spans and guide wraps together): the
    strands that vibrate longitudinally between the sprockets."""
    sprockets = {s["name"] for s in geometry["sprockets"]}
    segs = geometry["segments"]
    first = next(i for i, s in enumerate(segs) if s["kind"] == "wrap" and s["element"] in sprockets)
    strands, current = [], dict(start=segs[first]["element"], length=0.0)
    for s in segs[first + 1:] + segs[:first + 1]:
        if s["kind"] == "wrap" and s["element"] in sprockets:
            strands.append(dict(current, end=s["element"]))
            current = dict(start=s["element"], length=0.0)
        else:
            current["length"] += s["length"]
    return strands


def damping_measures(factors=(1.0, 4.0, 10.0)):
    """The project's damping values (and the raised ones) as damping ratios and restitution
    coefficients, the measures in which the literature states them."""
    d = default_drive_json()
    ch = d["chain"]
    m, k, c, p = ch["linkMass"], ch["joint"]["stiffness"], ch["joint"]["damping"], ch["pitch"]
    strand = max(strand_lengths(geometry()), key=lambda s: s["length"])
    wave = p * math.sqrt(k / m)                  # [m/s] longitudinal wave speed of the chain
    f1 = wave / (2.0 * strand["length"])         # [Hz] first longitudinal mode, strand fixed at both ends
    out = dict(linkMass=m, jointStiffness=k, jointDamping=c, pitch=p, rollerDiameter=ch["rollerDiameter"],
               strandLength=strand["length"],
               strandFrequency=f1, waveSpeed=wave, factors=list(factors), rows=[])
    for f in factors:
        cf_ = c * f
        roller = d["contact"]["rollerSprocket"]["dampingFactor"] * f
        guide = d["contact"]["plateGuide"]["dampingFactor"] * f
        out["rows"].append(dict(
            factor=f, jointDamping=cf_,
            zetaOneJoint=cf_ / (2.0 * math.sqrt(k * m)),      # one link against one joint
            zetaHighest=2.0 * cf_ / (2.0 * math.sqrt(k * m)),  # neighbours in antiphase: 4k, 4c
            zetaStrand=math.pi * f1 * cf_ / k,                # stiffness-proportional: zeta = omega c / (2 k)
            rollerAlpha=roller, rollerRestitution=[hunt_crossley_restitution(roller, v) for v in ROLLER_SPEEDS],
            guideAlpha=guide, guideRestitution=[hunt_crossley_restitution(guide, v) for v in GUIDE_SPEEDS]))
    return out


def damping_section(dm):
    rows = dm["rows"]
    head = "| measure | " + " | ".join(f"{r['factor']:g}x" for r in rows) + " |"
    L = ["## The damping values against the literature", "",
         f"Chain joint: k = {dm['jointStiffness']:.3g} N/m, link mass {dm['linkMass'] * 1e3:g} g, longest strand "
         f"between two sprockets {dm['strandLength'] * 1e3:.0f} mm (first longitudinal mode fixed-fixed "
         f"{dm['strandFrequency']:.0f} Hz, wave speed {dm['waveSpeed']:.0f} m/s). Joint damping is "
         "stiffness-proportional, so its damping ratio grows with frequency: zeta = pi f c / k.", "",
         head, "|---|" + "---|" * len(rows),
         "| joint damping c [N s/m] | " + " | ".join(f"{r['jointDamping']:g}" for r in rows) + " |",
         "| zeta, one link on one joint | " + " | ".join(f"{100 * r['zetaOneJoint']:.1f} %" for r in rows) + " |",
         "| zeta, highest link mode (neighbours in antiphase) | " + " | ".join(
             f"{100 * r['zetaHighest']:.0f} %" for r in rows) + " |",
         f"| zeta, first longitudinal strand mode ({dm['strandFrequency']:.0f} Hz) | " + " | ".join(
             f"{100 * r['zetaStrand']:.1f} %" for r in rows) + " |",
         "| roller-sprocket alpha [s/m] | " + " | ".join(f"{r['rollerAlpha']:g}" for r in rows) + " |"]
    for i, v in enumerate(ROLLER_SPEEDS):
        L.append(f"| roller-sprocket restitution e at {v:g} m/s | " + " | ".join(
            f"{r['rollerRestitution'][i]:.2f}" for r in rows) + " |")
    L.append("| plate-guide alpha [s/m] | " + " | ".join(f"{r['guideAlpha']:g}" for r in rows) + " |")
    for i, v in enumerate(GUIDE_SPEEDS):
        L.append(f"| plate-guide restitution e at {v:g} m/s | " + " | ".join(
            f"{r['guideRestitution'][i]:.2f}" for r in rows) + " |")
    L += ["", "Restitution: one impact integrated under the project's law F = k d (1 + 1.5 alpha d') clamped at zero "
          "(`hunt_crossley_restitution`); with exponent 1 it depends on alpha v only, and e ~ 1 - alpha v only "
          "while alpha v << 1.", ""]
    return L + literature_lines(dm)


def roller_stokes_numbers(d_roller):
    """Impact Stokes numbers St = rho d v / (9 mu) (a sphere's, the definition of Joseph et al.)
    of a steel roller at the roller seating speeds, in hot and in warm engine oil."""
    return {mu: [STEEL_DENSITY * d_roller * v / (9.0 * mu) for v in ROLLER_SPEEDS] for mu in OIL_VISCOSITY}


def literature_lines(dm):
    """What the stored public literature gives on chain damping, and where the defaults sit."""
    st = roller_stokes_numbers(dm["rollerDiameter"])
    rows = {r["factor"]: r for r in dm["rows"]}
    lo, hi = min(min(v) for v in st.values()), max(max(v) for v in st.values())
    d, x4, x10 = rows[1.0], rows.get(4.0), rows.get(10.0)
    return [
        "### Published figures", "",
        "Found with the project's search of stored public pages, which for most papers holds only the first page "
        "(abstract and introduction): parameter tables deeper in the papers could not be read, and no number is "
        "quoted here that was not read.", "",
        "| topic | source | what it gives |", "|---|---|---|",
        "| chain dynamics | G. Hippmann, M. Arnold, M. Schittenhelm, \"Efficient simulation of bush and roller chain "
        "drives\", Multibody Dynamics 2005, ECCOMAS Thematic Conference, Madrid, 21-24 June 2005 | the dynamics of "
        "valve-train chain drives \"is dominated by the effects of high velocities and transient driving torques "
        "as well as by polygonal action and rotatory impacts\"; no damping figure on the readable page. |",
        "| chain joints | A. Becker, D. Meffert, B. Sauer, \"Friction and wear investigations on single chain joints\", "
        "Forschung im Ingenieurwesen 83 (2019) 53-63, doi:10.1007/s10010-019-00297-x | timing-chain joints run in "
        "mixed and boundary friction; admissible wear elongation 0.5 %. No damping figure. |",
        "| chain joints | S. L. Pedersen, J. M. Hansen, J. A. C. Ambrosio, \"A roller chain drive model including "
        "contact with guide-bars\", Multibody System Dynamics 12 (2004) 285-301 | links as spring-damper "
        "assemblies, roller-guide contact as a continuous force (the model used here); the values are beyond the "
        "readable first page. |",
        "| chain joints | MSC Adams Machinery, \"Create Chain - Roller\" (https://adams.thisaray.com/adams_machinery/"
        "dialogboxes/chain_geo_rol.html) | \"the stiffness and damping of the bushing connecting two links\" are "
        "user inputs; no value. |",
        "| roller impacts | FunctionBay RecurDyn Chain, \"Contact Characteristic Page\" (https://functionbay.com/"
        "documentation/onlinehelp/Documents/contactcharacteristicpage.htm) | f_n = k d^m1 + c (d'/abs(d')) "
        "abs(d')^m2 d^m3, \"k and c ... determined by an experimental method\"; no value. |",
        "| roller impacts | S. L. Pedersen, \"Model of contact between rollers and sprockets in chain-drive "
        "systems\", Archive of Applied Mechanics 74 (2005) 489-508 | roller-sprocket contact as a continuous "
        "contact force; values beyond the readable first page. |",
        "| roller impacts | M. S. Kim, G. E. Johnson, \"A general multi-body dynamic model to predict the behavior "
        "of roller chain drives at moderate and high speeds\", University of Michigan, Deep Blue (year not on the "
        "readable page; http://deepblue.lib.umich.edu/bitstream/handle/2027.42/6004/bac0133.0001.001.txt) | engagement as \"a series of elastic collisions "
        "and rebounds\"; no value on the readable page. |",
        "| oil-wetted impacts | G. G. Joseph, R. Zenit, M. L. Hunt, A. M. Rosenwinkel, \"Particle-wall collisions "
        "in a viscous fluid\", Journal of Fluid Mechanics 433 (2001) 329-346 | no rebound below an impact Stokes "
        "number of about 10; above about 500 the restitution approaches its dry value (spheres of 3-12 mm). |",
        "| oil-wetted impacts | T. Mueller, K. Huang, \"Influence of the liquid film thickness on the coefficient of "
        "restitution for wet particles\" (arXiv:1601.07032, 2016); F. Gollwitzer, I. Rehberg, C. A. Kruelle, "
        "K. Huang, \"Coefficient of restitution for wet particles\" (arXiv:1202.1750, 2012) | the wet restitution "
        "falls linearly with 1/St; the film thickness relative to the particle size matters. |",
        "| PA66 guides | - | no figure for the damping or restitution of steel plates on polyamide guides was found. |",
        "",
        "### Where the defaults sit", "",
        f"- Roller seating impacts: the default alpha = {d['rollerAlpha']:g} s/m gives e = "
        + " / ".join(f"{e:.2f}" for e in d["rollerRestitution"]) + " at " + " / ".join(f"{v:g}" for v in ROLLER_SPEEDS)
        + " m/s. A steel roller of d = 6.35 mm in engine oil of 8.5 to 50 mPa s [E] meets the tooth at an impact "
        f"Stokes number St = rho d v / (9 mu) of {lo:.0f} to {hi:.0f}: far above the no-rebound limit of about 10 "
        "and partly above the dry limit of about 500 of Joseph et al. (a sphere's figures; a roller held by chain "
        "tension is an analogy, not a measurement). The oil film alone therefore does not make seating impacts "
        "plastic: their restitution lies between the wet and the dry value, so the default is on the dissipative "
        "side of plausible, 4x contact damping (e = " + " / ".join(f"{e:.2f}" for e in x4["rollerRestitution"])
        + ") asks for more dissipation than the oil film gives by this analogy, and 10x (e = "
        + " / ".join(f"{e:.2f}" for e in x10["rollerRestitution"]) + ") for impacts close to the no-rebound "
        "limit, which the analogy places near St = 10, far below the rollers' Stokes numbers. The drive's "
        "restitution for the rigid contact methods (rollerSprocket 0.5, plateGuide 0.3) matches the compliant "
        "law's values at 3-5 m/s and 1-3 m/s.",
        f"- Joint damping: {d['jointDamping']:g} N s/m is {100 * d['zetaOneJoint']:.0f} % of critical for one link on "
        f"one joint and {100 * d['zetaStrand']:.1f} % for the first longitudinal strand mode "
        f"({dm['strandFrequency']:.0f} Hz); being stiffness-proportional, it damps lower modes less (zeta = pi f c / "
        f"k: {100 * math.pi * 500.0 * d['jointDamping'] / dm['jointStiffness']:.2f} % at 500 Hz). No published "
        "figure was found to set it against; the joints run in mixed and boundary friction (Becker et al.), whose "
        "dissipation a viscous damper represents only on average. 4x and 10x give "
        f"{100 * x4['zetaStrand']:.0f} % and {100 * x10['zetaStrand']:.0f} % on the strand mode and overdamp the "
        f"link modes ({100 * x4['zetaOneJoint']:.0f} % and {100 * x10['zetaOneJoint']:.0f} % of critical on one "
        "joint); they also cost a 2x and 5x smaller explicit step.",
        f"- Plate-guide contacts: alpha = {d['guideAlpha']:g} s/m gives e = "
        + " / ".join(f"{e:.2f}" for e in d["guideRestitution"]) + " at " + " / ".join(f"{v:g}" for v in GUIDE_SPEEDS)
        + " m/s; with no published figure for steel on PA66 found, it stays an engineering estimate [E].",
        "",
    ]
