"""What the Python module adds (docs/python.md, issue 40's goals), measured in one run:

1. A run of the reference on the default scene (scenes/thesis_free_rocking.toml): the time of
   rockbench.run(scene) against the C++ time of its work inside the call (Result.core_s: the
   ground motion and the engine's run), the difference being what Python adds (the scene's
   checks, the thread, the GIL, the summary). Then the same with the history's arrays read.
2. A study of 1,000 members (scenes/studies/pulse_block.toml's block under one-sine pulses
   of amplitudes 0.2 to 1 g, the reference): `rockbench
   ensemble` against rockbench.study, the same jobs, alternated, the rate in runs per second.

    PYTHONPATH=build/python python3 bench/python_overhead.py [--members 1000] [--jobs 2]
"""

import argparse
import os
import statistics
import subprocess
import tempfile
import time

import rockbench

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.environ.get("ROCKBENCH_EXE", os.path.join(ROOT, "build", "src", "cli", "rockbench"))

# The base scene of the pulse studies: a 1 m x 4 m block under a one-sine pulse, for 12 s.
BLOCK = os.path.join(ROOT, "scenes", "studies", "pulse_block.toml")


def run_overhead(repeats):
    scene = rockbench.Scene.from_toml(os.path.join(ROOT, "scenes", "thesis_free_rocking.toml"))
    for _ in range(20):
        rockbench.run(scene)
    added, added_read, totals, cores = [], [], [], []
    for _ in range(repeats):
        start = time.perf_counter()
        r = rockbench.run(scene)
        total = time.perf_counter() - start
        added.append(total - r.core_s)
        totals.append(total)
        cores.append(r.core_s)
        start = time.perf_counter()
        r = rockbench.run(scene)
        _ = r.history["theta1"], r.history["theta2"]
        added_read.append(time.perf_counter() - start - r.core_s)
    med = statistics.median
    print(f"run of the reference on the default scene, {repeats} calls (medians):")
    print(f"  call {med(totals) * 1e3:.3f} ms, C++ work {med(cores) * 1e3:.3f} ms, "
          f"added by Python {med(added) * 1e3:.3f} ms "
          f"(90th percentile {sorted(added)[int(0.9 * len(added))] * 1e3:.3f} ms)")
    print(f"  with the history's arrays read: added {med(added_read) * 1e3:.3f} ms")


def study_rate(members, jobs, rounds):
    folder = tempfile.mkdtemp(prefix="rockbench_bench_")
    values = ", ".join(f"{0.2 + 0.8 * i / members:.6f}" for i in range(members))
    study = os.path.join(folder, "study.toml")
    with open(study, "w") as f:
        f.write(f'scene = "{BLOCK}"\nengines = ["reference"]\n\n[[axis]]\n'
                f'key = "base.horizontal.amplitude_g"\nvalues = [{values}]\n')
    cli_s, py_s = [], []
    for k in range(rounds):
        start = time.perf_counter()
        subprocess.run([EXE, "ensemble", study, "--out", os.path.join(folder, f"cli{k}"),
                        "--jobs", str(jobs)], check=True, capture_output=True)
        cli_s.append(time.perf_counter() - start)
        start = time.perf_counter()
        rockbench.study(study, os.path.join(folder, f"py{k}"), jobs=jobs, progress=False)
        py_s.append(time.perf_counter() - start)
    best_cli, best_py = min(cli_s), min(py_s)
    print(f"study of {members} members, {jobs} jobs, best of {rounds} alternated rounds:")
    print(f"  rockbench ensemble {best_cli:.2f} s ({members / best_cli:.0f} runs/s), "
          f"rockbench.study {best_py:.2f} s ({members / best_py:.0f} runs/s): "
          f"Python's rate is {100 * (best_cli / best_py):.1f}% of the CLI's")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--repeats", type=int, default=200)
    p.add_argument("--members", type=int, default=1000)
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--rounds", type=int, default=3)
    a = p.parse_args()
    run_overhead(a.repeats)
    study_rate(a.members, a.jobs, a.rounds)


if __name__ == "__main__":
    main()
