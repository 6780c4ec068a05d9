"""The floor under the routes to a quarter of real time (harness/bench/realtime_floor.py): its
formula, the stage shares read from a profile, and that the functions it counts as contact work
are the solver's."""
import pathlib

import pytest

from harness.bench import realtime_floor

ROOT = pathlib.Path(__file__).resolve().parents[2]

PERF_REPORT = """\
# Samples: 8K of event 'cpu-clock:ppp'
#
    18.51%  chaindrive-run  chaindrive-run        [.] chaindrive::(anonymous namespace)::rollersAvx2
    15.88%  chaindrive-run  chaindrive-run        [.] chaindrive::(anonymous namespace)::kinematicsAvx2
     8.35%  chaindrive-run  chaindrive-run        [.] chaindrive::(anonymous namespace)::platesAvx2
     4.56%  chaindrive-run  chaindrive-run        [.] Eigen::internal::gebp_kernel<double, double, long>::operator()
     2.86%  chaindrive-run  chaindrive-run        [.] chaindrive::ToothGap::closestOffSeat
     0.26%  chaindrive-run  libc.so.6             [.] __GI___printf_fp_l
     0.27%  chaindrive-run  [kernel.kallsyms]     [k] clear_page_erms
"""


def test_stage_shares_sort_the_functions_into_contact_work_the_rest_and_outside_the_steps():
    shares = realtime_floor.stage_shares(PERF_REPORT)
    assert shares["contact"] == pytest.approx(18.51 + 8.35 + 2.86)
    assert shares["rest"] == pytest.approx(15.88)
    assert shares["outside"] == pytest.approx(4.56 + 0.26)  # (the kernel's samples in none)


def test_the_floor_keeps_the_links_in_contact_at_the_fine_step_and_frees_the_others():
    # RTF 0.8 at 4 us; at a fine step of 5 us the work scales by 0.8; contact work 40 % of it stays,
    # the other 60 % only for the quarter of the links in contact
    contact, rest = realtime_floor.floor_parts(0.8, 4e-6, 5e-6, 0.4, 0.25)
    assert contact == pytest.approx(0.8 * 0.8 * 0.4) and rest == pytest.approx(0.8 * 0.8 * 0.6 * 0.25)
    # nothing in contact and no contact work: the floor is zero
    assert sum(realtime_floor.floor_parts(0.8, 4e-6, 5e-6, 0.0, 0.0)) == 0.0


def test_the_floor_against_the_target_gives_the_contact_speed_up_it_would_need():
    # 3000 rpm (target 0.25): RTF 0.8 at 4 us, fine step 5 us, contact work 50 %, 30 of 120 links
    speed = dict(rpm=3000.0, method="fixed-verlet", step=4e-6, rtf=0.8)
    f = realtime_floor.floor_of(speed, 5e-6, 120, dict(contactShare=0.5, contactPoints=30.0, outsidePercent=1.0))
    contact, rest = 0.8 * 0.8 * 0.5, 0.8 * 0.8 * 0.5 * 0.25
    assert f["floor"] == pytest.approx(contact + rest) and f["targetBelowFloor"]
    assert contact / f["contactSpeedupForTarget"] + rest == pytest.approx(f["rtfTarget"])
    # at half the RTF the floor meets the target: no speed-up asked
    met = realtime_floor.floor_of(dict(speed, rtf=0.4), 5e-6, 120, dict(contactShare=0.5, contactPoints=30.0,
                                                                         outsidePercent=1.0))
    assert not met["targetBelowFloor"] and met["contactSpeedupForTarget"] is None
    # every link in contact and little contact work: out of reach even with the contact work free
    full = realtime_floor.floor_of(speed, 5e-6, 120, dict(contactShare=0.1, contactPoints=120.0, outsidePercent=1.0))
    assert full["targetBelowFloor"] and full["contactSpeedupForTarget"] is None


def test_a_function_counts_as_contact_work_by_its_own_name_only():
    assert realtime_floor.stage_of("chaindrive::(anonymous namespace)::rollersAvx2") == "contact"
    assert realtime_floor.stage_of("chaindrive::controllersStep") == "rest"
    assert realtime_floor.stage_of("Eigen::internal::gebp_kernel<double>") == "outside"


def test_the_contact_functions_are_the_solvers():
    sources = "".join(p.read_text() for p in (ROOT / "src").rglob("*.cpp"))
    for name in realtime_floor.CONTACT_FUNCTIONS:
        assert f"{name}(" in sources or f"{name}Body(" in sources or f"{name}Avx2" in sources, name
