#!/usr/bin/env python3
"""An external engine that leaves something other than a poses file where its poses belong,
for the poses reader's refusals (tests/external/hostile_inputs_test.cc).

    python3 hostile_poses_engine.py MODE INPUT.json

  fifo     a FIFO (named pipe) that nobody writes: reading it would wait for ever
  devzero  a symbolic link to /dev/zero: endless zero bytes
  folder   a folder
  sparse   a sparse file of 100 GB (no block of it on disk)
  nul      a valid file whose second row's angle is `0.1<NUL>junk`
"""
import json
import os
import sys


def main(mode, input_path):
    with open(input_path) as f:
        run = json.load(f)
    poses = run["poses_file"]
    if mode == "fifo":
        os.mkfifo(poses)
    elif mode == "devzero":
        os.symlink("/dev/zero", poses)
    elif mode == "folder":
        os.mkdir(poses)
    elif mode == "sparse":
        with open(poses, "wb") as f:
            f.truncate(100 * 10**9)
    elif mode == "nul":
        dt = run["time_step_s"] * run["output_every_steps"]
        y = run["blocks"][0]["y_m"]
        with open(poses, "wb") as f:
            f.write(b"t_s,x1_m,y1_m,angle1_rad\n")
            for j in range(run["rows"]):
                angle = b"0.1\x00junk" if j == 1 else b"0"
                f.write(b"%r,0,%r,%s\n" % (j * dt, y, angle))
    else:
        sys.exit("unknown mode " + mode)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
