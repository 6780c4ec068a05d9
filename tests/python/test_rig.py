"""python -m harness rig end to end: the six loops run through chaindrive-rig, the picture and the
figures the docs quote are written, and the loops behave as the device must (the force never
below zero, the check valve holding the bottom of every loop near (p_s - p_crack) A = 32.8 N,
the peak rising with the frequency at 0.05 mm and with the amplitude, 0.2 mm capped near the
relief valve's 1.13 kN)."""
import json
import subprocess
import sys

from harness import paths


def test_rig_loops(tmp_path):
    out = tmp_path / "loops.png"
    result = subprocess.run([sys.executable, "-m", "harness", "rig", "--out", str(out), "--csv-dir", str(tmp_path)],
                            cwd=paths.ROOT, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert out.stat().st_size > 20000
    loops = {loop["name"]: loop for loop in json.loads(out.with_suffix(".json").read_text())["loops"]}
    assert len(loops) == 6
    for loop in loops.values():
        assert 0.0 <= loop["leastForce"] <= 32.8 * 1.01
    peaks = [loops[f"{f}Hz-0.05mm"]["peakForce"] for f in (20, 100, 200)]
    assert peaks == sorted(peaks)
    for f in (20, 100, 200):
        assert loops[f"{f}Hz-0.2mm"]["peakForce"] > loops[f"{f}Hz-0.05mm"]["peakForce"]
        assert 1.13e3 <= loops[f"{f}Hz-0.2mm"]["peakForce"] < 1.3e3
