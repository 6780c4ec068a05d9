"""python -m harness bench-threads on a short run: its figures where the answer is known (one
thread crosses no barrier and is its own ratio; two threads cross the 8 a step the real-time method
makes: 4 pool runs and 4 barriers within them, and a few more where the search windows are
scanned again), the states bit-identical, the pool's costs measured."""
import json

from harness import cli


def test_bench_threads_counts_the_barriers_of_a_step(tmp_path):
    out = tmp_path / "threads.md"
    assert cli.main(["bench-threads", "--threads", "1", "2", "--duration", "0.005", "--repeats", "1",
                     "--out", str(out)]) == 0
    record = json.loads(out.with_suffix(".json").read_text())
    one, two = record["rows"]
    assert one["threads"] == 1 and one["barriersPerStep"] == 0.0 and one["ratio"] == 1.0
    assert two["threads"] == 2 and 8.0 <= two["barriersPerStep"] < 8.5, two
    assert record["poolRunMicroseconds"] > 0.0 and record["barrierMicroseconds"] > 0.0
    assert "the end states bit-identical" in out.read_text()
