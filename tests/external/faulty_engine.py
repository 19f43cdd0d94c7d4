#!/usr/bin/env python3
"""An external engine that fails on purpose, for the protocol's error paths
(tests/external/external_engine_test.cc).

    python3 faulty_engine.py MODE INPUT.json

It writes one block at rest on the ground (a valid poses file) unless MODE breaks it:
  good            the valid file
  nan             a NaN in the middle row's angle
  exit            says why on stderr and exits with code 3
  crash           kills itself with SIGSEGV
  hang            sleeps for ever (the wall-clock limit must end it)
  memory          holds 600 MiB (the memory limit must end it)
  few_rows        stops halfway
  backwards       the middle row's time goes backwards
  missing_column  no angle1_rad column
  no_file         exits 0 without writing the poses file
"""
import json
import os
import signal
import sys
import time


def main(mode, input_path):
    with open(input_path) as f:
        run = json.load(f)
    if mode == "exit":
        sys.stderr.write("faulty engine: cannot simulate this on purpose\n")
        sys.exit(3)
    if mode == "crash":
        os.kill(os.getpid(), signal.SIGSEGV)
    if mode == "hang":
        while True:
            time.sleep(1)
    if mode == "memory":
        hog = bytearray(600 * 1024 * 1024)
        for i in range(0, len(hog), 4096):
            hog[i] = 1
        time.sleep(60)
    if mode == "no_file":
        return
    blocks = run["blocks"]
    dt, steps, every = run["time_step_s"], run["steps"], run["output_every_steps"]
    rows = [n for n in range(0, steps + 1, every)]
    if rows[-1] != steps:
        rows.append(steps)
    header = ["t_s"]
    for k in range(1, len(blocks) + 1):
        header += ["x%d_m" % k, "y%d_m" % k]
        if mode != "missing_column":
            header.append("angle%d_rad" % k)
    middle = len(rows) // 2
    with open(run["poses_file"], "w") as out:
        out.write(",".join(header) + "\n")
        for j, n in enumerate(rows):
            if mode == "few_rows" and j == middle:
                break
            t = n * dt
            if mode == "backwards" and j == middle:
                t = (rows[j - 2]) * dt
            fields = ["%.17g" % t]
            for k, b in enumerate(blocks):
                fields += ["%.17g" % b["x_m"], "%.17g" % b["y_m"]]
                if mode != "missing_column":
                    fields.append("nan" if (mode == "nan" and j == middle) else "%.17g" % b["angle_rad"])
            out.write(",".join(fields) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
