"""The Python module against the command line: the same scene gives the same bytes, errors map to
exceptions with the command line's message, arrays are the caller's own, and Ctrl-C stops a long
call leaving nothing half-written. Run by CTest (tests/python/CMakeLists.txt) with PYTHONPATH at
the built package and ROCKBENCH_EXE the command-line program."""

import json
import math
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
import tomllib

import numpy as np
import pytest

import rockbench

SOURCE = os.environ["ROCKBENCH_SOURCE_DIR"]
EXE = os.environ["ROCKBENCH_EXE"]
HARMONIC = os.path.join(SOURCE, "scenes", "harmonic.toml")
RECORD_SCENE = os.path.join(SOURCE, "scenes", "thesis_rinaldi228.toml")


def cli(*args, check=True):
    p = subprocess.run([EXE, *args], capture_output=True, text=True)
    if check and p.returncode != 0:
        raise AssertionError(f"rockbench {' '.join(args)} exited {p.returncode}: {p.stderr}")
    return p


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


# Keys whose values are the wall clock's (or the machine's), not the run's: "wall_s" and every
# "..._wall_s", the rates and the external engines' process figures.
TIMING_KEYS = {"real_time_factor", "read_s", "monitor_s", "overhead_s", "peak_resident_mib"}


def is_timing(key):
    return key in TIMING_KEYS or key == "wall_s" or key.endswith("_wall_s")


def without_timing(value):
    if isinstance(value, dict):
        return {k: without_timing(v) for k, v in value.items() if not is_timing(k)}
    if isinstance(value, list):
        return [without_timing(v) for v in value]
    return value


@pytest.mark.parametrize("engine", ["reference", "bullet"])
def test_run_gives_the_command_lines_bytes(tmp_path, engine):
    cli("run", HARMONIC, "--engine", engine, "--out", str(tmp_path))
    r = rockbench.run(rockbench.Scene.from_toml(HARMONIC), engine)
    assert r.history_csv() == read(tmp_path / engine / "history.csv")
    assert r.events_csv() == read(tmp_path / engine / "events.csv")
    cli_summary = json.loads(read(tmp_path / "summary.json"))
    assert without_timing(r.summary) == without_timing(cli_summary)


def test_history_columns_are_the_runs_doubles(tmp_path):
    r = rockbench.run(HARMONIC)
    assert r.history.columns == read_header(r.history_csv())
    table = np.genfromtxt(r.history_csv().splitlines()[1:], delimiter=",", dtype=None,
                          encoding="utf-8")
    assert r.history.samples == len(table)
    for i, name in enumerate(r.history.columns):
        if name == "mode":
            assert r.history["mode"] == [str(row[i]) for row in table]
            continue
        column = np.array([row[i] for row in table], dtype=float)
        # history.csv prints 13 significant digits (%.12e; times %.9f): the file's value is
        # within half a unit of its last digit of the exact double.
        scale = np.maximum(np.abs(r.history[name]), 1e-300)
        limit = 5e-13 * scale if name != "t" else np.full_like(scale, 5e-10)
        assert np.all(np.abs(r.history[name] - column) <= limit), name
    assert r.history["theta1"].dtype == np.float64


def read_header(text):
    return text.splitlines()[0].split(",")


def test_a_dict_scene_is_the_toml_scene():
    with open(HARMONIC, "rb") as f:
        d = tomllib.load(f)
    from_file = rockbench.run(HARMONIC)
    from_dict = rockbench.run(rockbench.Scene.from_dict(d))
    assert from_dict.history_csv() == from_file.history_csv()
    assert from_dict.events_csv() == from_file.events_csv()


def test_to_toml_reads_back_as_the_same_scene():
    scene = rockbench.Scene.from_toml(RECORD_SCENE, overrides=["run.duration=2"])
    text = scene.to_toml()
    again = rockbench.Scene.from_toml(text)
    assert again.duration_s == 2.0
    # The record's path is made absolute, so the text runs from any folder.
    assert os.path.isabs(again.to_dict()["base"]["horizontal"]["file"])
    assert rockbench.run(again).history_csv() == rockbench.run(scene).history_csv()


def test_settings_are_the_command_lines_set(tmp_path):
    cli("run", HARMONIC, "--set", "model.rtol=1e-8", "--set", "model.integrator=\"dop853\"",
        "--out", str(tmp_path))
    r = rockbench.run(HARMONIC, rtol=1e-8, integrator="dop853")
    assert r.history_csv() == read(tmp_path / "reference" / "history.csv")
    # The setting took: another tolerance gives another history.
    assert rockbench.run(HARMONIC).history_csv() != r.history_csv()


def cli_error(scene_path):
    p = cli("run", str(scene_path), "--out", str(scene_path) + ".out", check=False)
    assert p.returncode == 2, p.stderr
    return p.stderr


@pytest.mark.parametrize(
    "mutation, key",
    [
        (lambda d: d["block1"].update(widht=1.0), "block1.widht"),
        (lambda d: d["block1"].update(width=-1.0), "block1.width"),
        (lambda d: d["base"]["horizontal"].update(amplitude_g=float("nan")),
         "base.horizontal.amplitude_g"),
        (lambda d: d["run"].update(duration="long"), "run.duration"),
    ],
)
def test_errors_raise_value_error_with_the_command_lines_message(tmp_path, mutation, key):
    with open(HARMONIC, "rb") as f:
        d = tomllib.load(f)
    mutation(d)
    path = tmp_path / "bad.toml"
    path.write_text(rockbench._dict_to_toml(d))
    stderr = cli_error(path)
    with pytest.raises(ValueError) as e:
        rockbench.run(rockbench.Scene.from_toml(str(path)))
    message = str(e.value)
    assert key in message
    # The same message as the command line's, which names the file and line too.
    assert message in stderr, (message, stderr)


def test_missing_file_and_unknown_engine_raise_value_error(tmp_path):
    with pytest.raises(ValueError, match="no such scene file"):
        rockbench.Scene.from_toml(str(tmp_path / "absent.toml"))
    with pytest.raises(ValueError, match="nosuchengine"):
        rockbench.run(HARMONIC, "nosuchengine")
    with pytest.raises(ValueError, match="block1"):
        rockbench.Scene.from_dict({"block1": {"width": 1.0, "height": 2.0, "density": "x"}})


def test_arrays_are_the_callers_own():
    r = rockbench.run(HARMONIC)
    theta = r.history["theta1"]
    kept = theta.copy()
    theta[:] = 7.0
    assert theta.flags.owndata or theta.base is not None
    # rockbench's state is untouched: the file text and a new run are what they were.
    again = rockbench.run(HARMONIC)
    assert np.array_equal(again.history["theta1"], kept)
    assert "7.000000000000e+00" not in r.history_csv()


def test_compare_is_comparison_json(tmp_path):
    cli("compare", HARMONIC, "--engines", "bullet", "--quick", "--out", str(tmp_path))
    c = rockbench.compare(HARMONIC, engines=["bullet"], members=0, progress=False)
    expected = json.loads(read(tmp_path / "comparison.json"))
    assert without_timing(dict(c)) == without_timing(expected)
    assert c["engines"]["bullet"]["verdict_kind"] == expected["engines"]["bullet"]["verdict_kind"]
    assert set(c.runs) == {"reference", "bullet"}
    assert c.runs["bullet"].history_csv() == read(tmp_path / "bullet" / "history.csv")
    assert c.failures == []


def test_compare_of_a_cylinder_is_comparison_json(tmp_path):
    # A cylinder (issue 41): the tilt vector's two components, their local tolerance, and "all"
    # leaving the planar engines out as the command line does.
    scene = os.path.join(SOURCE, "scenes", "three_d", "cylinder_rotating_harmonic.toml")
    cli("compare", scene, "--engines", "ode", "--quick", "--out", str(tmp_path))
    c = rockbench.compare(scene, engines=["ode"], members=0, progress=False)
    expected = json.loads(read(tmp_path / "comparison.json"))
    assert without_timing(dict(c)) == without_timing(expected)
    assert {"tilt_x1", "tilt_y1"} <= set(c["engines"]["ode"])
    assert set(c.local_tolerance) == {"tilt_x1", "tilt_y1"}
    assert np.array_equal(
        c.local_tolerance["tilt_x1"]["tolerance_rad"], c.local_tolerance["tilt_y1"]["tolerance_rad"]
    )
    planar = [e["name"] for e in rockbench.engines() if e["built"] and e["name"] in ("box2d", "rapier")]
    if planar:
        with pytest.warns(rockbench.RockbenchWarning, match="compare: not run: .*block1.shape"):
            rockbench.compare(scene, engines="all", members=0, progress=False)


def test_engines_lists_the_builds_engines():
    listed = rockbench.engines()
    assert listed[0]["name"] == "reference" and listed[0]["built"]
    text = cli("engines").stdout
    for e in listed[1:]:
        line = next(l for l in text.splitlines() if l.startswith(e["name"]))
        assert ("left out" in line) == (not e["built"]), line
        if not e["built"]:
            assert e["reason"]


def test_the_gil_is_released_while_cpp_runs():
    # A Python thread counts while the main thread is inside a run of the reference: with the
    # GIL held throughout, it could not count at all during the call.
    scene = rockbench.Scene.from_toml(RECORD_SCENE, overrides=["run.duration=20"])
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.001)

    t = threading.Thread(target=count)
    t.start()
    time.sleep(0.01)
    start = time.monotonic()
    rockbench.run(scene, "bullet")
    end = time.monotonic()
    stop.set()
    t.join()
    during = [x for x in ticks if start < x < end]
    assert end - start > 0.05
    assert len(during) >= 5, (end - start, len(during))


STUDY = textwrap.dedent(
    """
    title = "interrupt test"
    scene = "block.toml"
    engines = ["{engine}"]

    [[axis]]
    key = "base.horizontal.amplitude_g"
    values = [{values}]
    """
)

BLOCK = textwrap.dedent(
    """
    [block1]
    width = 0.3
    height = 1.2
    density = 2000.0

    [base.horizontal]
    kind = "sine_pulse"
    amplitude_g = 0.3
    frequency_hz = 1.0

    [run]
    duration = {duration}
    output_interval = 0.01
    """
)


def write_study(folder, members, duration, engine="reference"):
    values = ", ".join(f"{0.2 + 0.6 * i / members:.4f}" for i in range(members))
    (folder / "block.toml").write_text(BLOCK.format(duration=duration))
    (folder / "study.toml").write_text(STUDY.format(values=values, engine=engine))
    return folder / "study.toml"


def test_study_from_python_is_the_command_lines(tmp_path):
    study = write_study(tmp_path, 12, 2.0)
    cli("ensemble", str(study), "--out", str(tmp_path / "cli"), "--jobs", "2")
    frame = rockbench.study(study, tmp_path / "py", jobs=2, progress=False)
    assert len(frame) == 12
    cli_rows = read(tmp_path / "cli" / "members.csv").splitlines()
    py_rows = read(tmp_path / "py" / "members.csv").splitlines()
    header = cli_rows[0].split(",")
    wall = header.index("wall_s") if "wall_s" in header else None

    def strip(rows):
        out = []
        for row in rows:
            cells = row.split(",")
            if wall is not None:
                cells[wall] = ""
            out.append(cells)
        return out

    assert strip(py_rows) == strip(cli_rows)
    assert list(frame.columns) == header


INTERRUPTED = textwrap.dedent(
    """
    import sys, rockbench
    print("started", flush=True)
    try:
        rockbench.study(sys.argv[1], sys.argv[2], jobs=2, progress=False)
    except KeyboardInterrupt:
        print("KeyboardInterrupt", flush=True)
        sys.exit(0)
    print("finished", flush=True)
    """
)


def test_ctrl_c_stops_a_study_and_leaves_nothing_half_written(tmp_path):
    # Bullet's runs of 20 s take a good fraction of a second each: the study is still running
    # when Ctrl-C comes.
    study = write_study(tmp_path, 400, 20.0, engine="bullet")
    out = tmp_path / "out"
    env = dict(os.environ)
    p = subprocess.Popen([sys.executable, "-c", INTERRUPTED, str(study), str(out)],
                         stdout=subprocess.PIPE, text=True, env=env)
    assert p.stdout.readline().strip() == "started"
    # Some rows first, then Ctrl-C.
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        members = out / "members.csv"
        if members.exists() and len(read(members).splitlines()) >= 3:
            break
        time.sleep(0.05)
    p.send_signal(signal.SIGINT)
    stdout, _ = p.communicate(timeout=60)
    assert "KeyboardInterrupt" in stdout
    leftovers = [n for n in os.listdir(out) if ".tmp." in n]
    assert leftovers == []
    text = read(out / "members.csv")
    assert text.endswith("\n")  # whole rows only
    rows = text.splitlines()
    assert 2 <= len(rows) < 401
    # No worker outlives the call.
    time.sleep(0.2)
    # pgrep without the sanitizer's runtime that the ASan build preloads into Python (it
    # would hang in a program not built for it).
    plain = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}
    ps = subprocess.run(["pgrep", "-f", f"ensemble {study}"], capture_output=True, text=True,
                        env=plain)
    assert ps.stdout.strip() == ""


def test_ctrl_c_stops_a_compare(tmp_path):
    code = textwrap.dedent(
        f"""
        import rockbench, sys
        print("started", flush=True)
        try:
            rockbench.compare({RECORD_SCENE!r}, engines=["bullet"], members=4000,
                              engine_members=0, jobs=1, progress=False)
        except KeyboardInterrupt:
            print("KeyboardInterrupt", flush=True)
            sys.exit(0)
        print("finished", flush=True)
        """
    )
    # 4000 reference members of a 20 s record on one thread take about a minute: Ctrl-C comes
    # while they run.
    p = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "started"
    time.sleep(4.0)
    start = time.monotonic()
    p.send_signal(signal.SIGINT)
    stdout, _ = p.communicate(timeout=120)
    assert "KeyboardInterrupt" in stdout
    # The members' pool takes no new member: it stops within a member's run or two.
    assert time.monotonic() - start < 30


def samples_scene(tmp_path, accel, **extra):
    """The thesis's stack under `accel` (g, every 5 ms) from numpy, and the same record as a
    one-column file."""
    d = {
        "block1": {"width": 1.25, "height": 1.25, "density": 2500.0},
        "block2": {"width": 1.0, "height": 2.5, "density": 2500.0},
        "base": {"horizontal": {"samples": accel, "dt": 0.005, "units": "g", **extra}},
        "run": {"duration": 4.0, "output_interval": 0.005},
    }
    record = tmp_path / "record.txt"
    record.write_text("".join(f"{repr(float(a))}\n" for a in accel))
    text = rockbench._dict_to_toml({**d, "base": {"horizontal": {
        "file": str(record), "dt": 0.005, "units": "g"}}})
    path = tmp_path / "file.toml"
    path.write_text(text)
    return d, path


def test_samples_from_numpy_are_the_record_file(tmp_path):
    t = np.arange(0.0, 3.0, 0.005)
    accel = 0.5 * np.sin(2 * np.pi * 1.5 * t) * np.exp(-t)
    d, path = samples_scene(tmp_path, accel)
    cli("run", str(path), "--out", str(tmp_path / "cli"))
    r = rockbench.run(rockbench.Scene.from_dict(d))
    assert r.history_csv() == read(tmp_path / "cli" / "reference" / "history.csv")
    # The motion moved the stack (the check could fail): its peak is well above rounding.
    assert np.max(np.abs(r.history["theta2"])) > 1e-3
    assert r.summary["base"]["horizontal"]["format"] == "samples"


def test_a_bad_sample_is_named(tmp_path):
    accel = np.zeros(100)
    accel[7] = np.nan
    with pytest.raises(ValueError, match=r"base\.horizontal\.samples\[7\]: expected a finite"):
        rockbench.Scene.from_dict(samples_scene(tmp_path, accel)[0])
    with pytest.raises(ValueError, match=r"base\.horizontal\.resolution"):
        rockbench.Scene.from_dict(samples_scene(tmp_path, np.zeros(10), resolution=-1.0)[0])
