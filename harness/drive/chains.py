"""ISO 606 simplex roller chains by designation, for the layout aid (layout.py): the standard's
dimensions and what a drive description needs besides them, each number with where it comes from,
because the drive's stable step depends on the link's mass and the joint's stiffness
(docs/defaults.md).

Sources: ISO 606 and vendor tables as collected in the timing-drive reference sheet (pitch, roller
diameter, plate height, mass per metre); the default drive's chain (docs/default_drive.md); the
rest estimated: the link inertia with half the mass at the pins and the plates as pitch x height
rectangles (the default drive's rule), the joint stiffness the default's 1.2e8 N/m for 06B-1
scaled by the pitch squared, the joint damping the default's.
"""
import dataclasses

from . import design

JOINT_STIFFNESS_06B = design.JOINT_K   # [N/m] the default drive's (per-link stiffness typically 1e8-1.5e8)
JOINT_DAMPING = design.JOINT_C         # [N s/m] the default drive's lubricated pin-bushing joint
PITCH_06B = design.PITCH


def estimated_link_inertia(mass, pitch, plate_h):
    """Half the mass at the pins, the plates as pitch x height rectangles [kg m^2] (the default
    drive's rule, docs/default_drive.md)."""
    return mass * (pitch**2 / 8.0 + (pitch**2 + plate_h**2) / 24.0)


def four_digits(value):
    return float(f"{value:.4g}")


@dataclasses.dataclass(frozen=True)
class ChainData:
    designation: str
    pitch: float            # [m]
    roller_d: float         # [m]
    plate_h: float          # [m]
    link_mass: float        # [kg]
    link_inertia: float     # [kg m^2]
    joint_stiffness: float  # [N/m]
    joint_damping: float    # [N s/m]
    sources: dict           # field -> where its value comes from

    @property
    def standard(self):
        return f"ISO 606 {self.designation} simplex roller chain"


def _iso606(designation, pitch, roller_d, plate_h, mass, sources, link_inertia=None):
    """A catalogue entry; mass per link [kg] (the table's mass per metre times the pitch)."""
    inertia = link_inertia if link_inertia is not None else four_digits(estimated_link_inertia(mass, pitch, plate_h))
    stiffness = four_digits(JOINT_STIFFNESS_06B * (pitch / PITCH_06B) ** 2)
    sources = dict(sources)
    sources.setdefault("linkInertia", "estimated: half the mass at the pins, plates as pitch x height rectangles")
    sources["joint.stiffness"] = "estimated: the default's 1.2e8 N/m (06B-1) scaled by the pitch squared"
    sources["joint.damping"] = "the default drive's 250 N s/m"
    return ChainData(designation, pitch, roller_d, plate_h, mass, inertia, stiffness, JOINT_DAMPING, sources)


CHAINS = {
    "05B-1": _iso606("05B-1", 0.008, 0.005, 0.00711, 0.00144, {
        "pitch": "ISO 606", "rollerDiameter": "ISO 606", "plateHeight": "ISO 606 (recalled, not in a retrieved source)",
        "linkMass": "0.18 kg/m (DIN 8187 vendor table) x pitch"}),
    "06B-1": _iso606("06B-1", design.PITCH, design.ROLLER_D, design.PLATE_H, design.LINK_MASS, {
        "pitch": "ISO 606", "rollerDiameter": "ISO 606", "plateHeight": "ISO 606 (recalled, not in a retrieved source)",
        "linkMass": "0.41 kg/m (DIN 8187 vendor table) x pitch: the default drive's 3.9 g",
        "linkInertia": "the default drive's 7.0e-8 kg m^2 (the estimate's rule, written to 1e-9)"},
        link_inertia=round(design.LINK_INERTIA, 9)),
    "08B-1": _iso606("08B-1", 0.0127, 0.00851, 0.01181, 0.008255, {
        "pitch": "ISO 606", "rollerDiameter": "ISO 606", "plateHeight": "ISO 606",
        "linkMass": "0.65 kg/m (ISO 606 vendor table; others give up to 0.70) x pitch"}),
}


def chain_data(designation):
    """The catalogue's chain; KeyError for a designation it does not hold."""
    return CHAINS[designation]
