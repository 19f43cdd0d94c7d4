"""rockbench: rocking rigid blocks, an analytical reference judged against physics engines.

The library the command line uses, from Python (docs/python.md):

    import rockbench
    scene = rockbench.Scene.from_toml("scenes/harmonic.toml")
    r = rockbench.run(scene)                       # the reference model
    r.history["theta1"]                            # numpy array, rad
    c = rockbench.compare(scene, engines=["bullet"], members=0)
    c["engines"]["bullet"]["verdict_kind"]

Scenes have the keys of the TOML files (docs/scenes.md). Errors in a scene raise ValueError
with the command line's message (file, line, key, what was expected). Long calls release the
GIL and stop on Ctrl-C (KeyboardInterrupt), leaving no file half-written.
"""

from __future__ import annotations

import csv
import io
import json
import math
import numbers
import os
import re
import sys
import time
import tomllib
import warnings
from collections.abc import Mapping

import numpy as np

from . import _core

__version__ = _core.version
__all__ = [
    "Scene",
    "History",
    "Result",
    "Comparison",
    "RockbenchWarning",
    "run",
    "compare",
    "engines",
    "study",
    "read_study",
]


class RockbenchWarning(UserWarning):
    """What the command line says on stderr about a run: a padded record, a run that failed
    (non_finite), a model that stopped deciding the motion, an engine a scene brings that was
    not run."""


# ---------------------------------------------------------------------------------------------
# TOML text from a dict (the scene's keys), so that a dict scene is read by the same reader.

_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


def _toml_key(key) -> str:
    key = str(key)
    return key if _BARE_KEY.match(key) else json.dumps(key, ensure_ascii=False)


def _toml_value(value, where: str) -> str:
    """One TOML value: bool, int, float (shortest round-trip text; inf and nan as TOML spells
    them), str, or an array of those (a list, tuple or numpy array)."""
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        x = float(value)
        if math.isnan(x):
            return "nan"
        if math.isinf(x):
            return "inf" if x > 0 else "-inf"
        return repr(x)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, os.PathLike):
        return json.dumps(os.fspath(value), ensure_ascii=False)
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v, f"{where}[{i}]") for i, v in enumerate(value)) + "]"
    raise ValueError(
        f"{where}: expected a number, a string, a bool or a list of them, "
        f"got {type(value).__name__}"
    )


def _is_table_list(value) -> bool:
    return isinstance(value, (list, tuple)) and len(value) > 0 and all(
        isinstance(v, Mapping) for v in value
    )


def _toml_table(table: Mapping, name: str, lines: list[str]) -> None:
    """Writes `table`'s plain keys, then its sub-tables ([name.key]) and arrays of tables
    ([[name.key]])."""
    for key, value in table.items():
        if isinstance(value, Mapping) or _is_table_list(value):
            continue
        where = f"{name}.{key}" if name else str(key)
        lines.append(f"{_toml_key(key)} = {_toml_value(value, where)}")
    for key, value in table.items():
        full = f"{name}.{_toml_key(key)}" if name else _toml_key(key)
        if isinstance(value, Mapping):
            lines.append("")
            lines.append(f"[{full}]")
            _toml_table(value, full, lines)
        elif _is_table_list(value):
            for item in value:
                lines.append("")
                lines.append(f"[[{full}]]")
                _toml_table(item, full, lines)


def _dict_to_toml(d: Mapping) -> str:
    if not isinstance(d, Mapping):
        raise ValueError(f"scene: expected a dict of the scene's keys, got {type(d).__name__}")
    lines: list[str] = []
    _toml_table(d, "", lines)
    return "\n".join(lines).lstrip("\n") + "\n"


def _override(key: str, value) -> str:
    return f"{key}={_toml_value(value, key)}"


# ---------------------------------------------------------------------------------------------


class Scene:
    """A scene: the blocks, the base motion, the run's and the model's settings
    (docs/scenes.md). Build one with Scene.from_toml or Scene.from_dict."""

    def __init__(self, core_scene):
        self._core = core_scene

    @classmethod
    def from_toml(cls, path_or_text, overrides=()) -> "Scene":
        """A scene from a TOML file (a str path or os.PathLike) or from TOML text (a str with a
        newline or an '='). `overrides` are "key=value" strings, as the command line's --set.
        Relative record paths are relative to the file's folder (to the working folder for
        text). Raises ValueError naming the file, line and key of an error."""
        overrides = [str(o) for o in overrides]
        if isinstance(path_or_text, os.PathLike) or (
            isinstance(path_or_text, str) and "\n" not in path_or_text and "=" not in path_or_text
        ):
            path = os.fspath(path_or_text)
            if not os.path.exists(path):
                raise ValueError(f"{path}: no such scene file")
            return cls(_core.load_scene(path, overrides))
        if not isinstance(path_or_text, str):
            raise ValueError(
                f"scene: expected a path or TOML text, got {type(path_or_text).__name__}"
            )
        return cls(_core.parse_scene(path_or_text, "", overrides))

    @classmethod
    def from_dict(cls, d: Mapping) -> "Scene":
        """A scene from a dict with the TOML file's keys and tables:
        {"block1": {"width": 1.25, ...}, "base": {"horizontal": {"kind": "harmonic", ...}}}.
        A base-motion table may give its record as samples: {"samples": numpy_array, "dt":
        0.01, "units": "m/s2"}. Raises ValueError naming the key of an error."""
        return cls(_core.parse_scene(_dict_to_toml(d), "", []))

    def to_dict(self) -> dict:
        """The scene's keys as a dict (the text it was read from with its overrides applied;
        record paths made absolute)."""
        d = tomllib.loads(self._core.toml_text)
        for o in self._core.overrides:
            key, _, value = o.partition("=")
            parts = key.strip().split(".")
            table = d
            for p in parts[:-1]:
                table = table.setdefault(p, {})
            table[parts[-1]] = tomllib.loads("v = " + value.strip())["v"]
        folder = os.path.dirname(os.path.abspath(self._core.path)) if self._core.path else None
        for motion in d.get("base", {}).values():
            if isinstance(motion, dict) and "file" in motion and folder is not None:
                motion["file"] = os.path.normpath(os.path.join(folder, motion["file"]))
        return d

    def to_toml(self) -> str:
        """The scene as TOML text that reads back as the same scene (Scene.from_toml)."""
        return _dict_to_toml(self.to_dict())

    def with_overrides(self, overrides) -> "Scene":
        """A copy with "key=value" overrides applied (as --set)."""
        overrides = list(self._core.overrides) + [str(o) for o in overrides]
        if self._core.path:
            return Scene(_core.load_scene(self._core.path, overrides))
        return Scene(_core.parse_scene(self._core.toml_text, "", overrides))

    @property
    def path(self) -> str:
        """The scene file ('' for a scene from text or a dict)."""
        return self._core.path

    @property
    def blocks(self) -> int:
        """The number of blocks (bodies) of the stack."""
        return self._core.blocks

    @property
    def title(self) -> str:
        return self._core.title

    @property
    def duration_s(self) -> float:
        """The simulated time, s (run.duration)."""
        return self._core.duration_s

    def __repr__(self) -> str:
        where = self.path or "text"
        return f"<rockbench.Scene {where!r}: {self.blocks} block(s), {self.duration_s:g} s>"


def _as_scene(scene) -> Scene:
    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, Mapping):
        return Scene.from_dict(scene)
    return Scene.from_toml(scene)


class History(Mapping):
    """A run's history: history.csv's columns by name, in its order. Numbers are numpy float64
    arrays holding the run's exact doubles (history.csv prints 13 significant digits); "mode" is
    a list of str. Every array is the caller's own copy."""

    def __init__(self, columns: dict):
        self._columns = dict(columns)

    def __getitem__(self, name):
        try:
            return self._columns[name]
        except KeyError:
            raise KeyError(
                f"{name!r}: no such column; the columns are {', '.join(self._columns)}"
            ) from None

    def __iter__(self):
        return iter(self._columns)

    def __len__(self):
        return len(self._columns)

    @property
    def columns(self) -> list[str]:
        return list(self._columns)

    @property
    def samples(self) -> int:
        """The number of samples (rows)."""
        return len(self._columns["t"])

    def to_pandas(self):
        """The history as a pandas DataFrame (pandas must be installed: python3-pandas)."""
        try:
            import pandas as pd
        except ImportError as e:
            raise ImportError("History.to_pandas needs pandas (Debian: python3-pandas)") from e
        return pd.DataFrame({k: self._columns[k] for k in self._columns})

    def __repr__(self) -> str:
        return f"<rockbench.History {self.samples} samples: {', '.join(self._columns)}>"


def _csv_columns(text: str) -> dict:
    """A CSV text's columns: numbers as float64 arrays, anything else as a list of str."""
    rows = list(csv.reader(io.StringIO(text)))
    if not rows:
        return {"t": np.zeros(0)}
    header, body = rows[0], rows[1:]
    out = {}
    for i, name in enumerate(header):
        cells = [r[i] for r in body]
        try:
            out[name] = np.array([float(c) for c in cells], dtype=np.float64)
        except ValueError:
            out[name] = cells
    return out


class Result:
    """One engine's run: .history (History), .events (events.csv's columns), .summary
    (summary.json as a dict), .status ("completed", "overturned", ... docs/outputs.md). The
    history's arrays and the files' text are made when first asked for."""

    def __init__(self, d: dict):
        self.engine: str = d["engine"]
        self.status: str = d["status"]
        self.summary: dict = json.loads(d["summary_json"])
        self.one_line: str = d["one_line"]
        self.wall_s: float = d["wall_s"]
        # The C++ time of the call's work (the ground motion and the engine's run), s.
        self.core_s: float = d["core_s"]
        self._record = d["record"]
        self._summary_json = d["summary_json"]
        self._history = None
        self._events = None

    @property
    def history(self) -> History:
        """history.csv's columns: r.history["theta1"] (rad), r.history["t"] (s), ..."""
        if self._history is None:
            self._history = History(self._record.history_columns())
        return self._history

    @property
    def events(self) -> History:
        """events.csv's columns (impacts, transitions, initiations, rest, overturn, ...)."""
        if self._events is None:
            self._events = History(_csv_columns(self.events_csv()))
        return self._events

    def history_csv(self) -> str:
        """history.csv's text, byte for byte the command line's."""
        return self._record.history_csv()

    def events_csv(self) -> str:
        """events.csv's text, byte for byte the command line's."""
        return self._record.events_csv()

    def save(self, out_dir) -> None:
        """Writes OUT/<engine>/history.csv and events.csv, and OUT/summary.json, as `rockbench
        run --out OUT` does: each to a temporary name, renamed when complete."""
        folder = os.path.join(os.fspath(out_dir), self.engine)
        os.makedirs(folder, exist_ok=True)
        _write_atomic(os.path.join(folder, "history.csv"), self.history_csv())
        _write_atomic(os.path.join(folder, "events.csv"), self.events_csv())
        _write_atomic(os.path.join(os.fspath(out_dir), "summary.json"), self._summary_json)

    def __repr__(self) -> str:
        return f"<rockbench.Result {self.engine}: {self.status}>"


def _write_atomic(path: str, text: str) -> None:
    tmp = f"{path}.tmp.{os.getpid()}"
    try:
        with open(tmp, "w", encoding="utf-8", newline="") as f:
            f.write(text)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def _warn(message: str) -> None:
    warnings.warn(message, RockbenchWarning, stacklevel=3)


def _settings_overrides(engine: str, settings: dict) -> list[str]:
    # The reference's settings are the scene's [model] keys; an engine's, its own table's.
    table = "model" if engine == "reference" else engine
    return [_override(f"{table}.{key}", value) for key, value in settings.items()]


def run(scene, engine: str = "reference", **settings) -> Result:
    """Runs one engine on a scene, as `rockbench run SCENE --engine ENGINE`.

    scene:    a Scene, a dict of the scene's keys, a TOML file path or TOML text.
    engine:   "reference" (the analytical model) or an engine of rockbench.engines().
    settings: the engine's settings (docs/engines.md): for the reference the [model] keys
              (rtol=1e-10, integrator="dop853"), for an engine its table's keys
              (run(scene, "bullet", time_step=1e-4)); as --set ENGINE.KEY=VALUE.

    Returns a Result: .history (numpy columns by name: r.history["theta1"]), .events,
    .summary (summary.json's keys), .status. Warns (RockbenchWarning) where the command line
    writes to stderr: a padded record, a run that ended non_finite, a model that stopped
    deciding the motion. Raises ValueError for a bad scene, setting or engine name.
    """
    s = _as_scene(scene)
    if settings:
        s = s.with_overrides(_settings_overrides(engine, settings))
    d = _core.run(s._core, engine)
    for note in d["notes"]:
        _warn(note)
    result = Result(d)
    if result.status == "non_finite":
        _warn(f"run failed: {engine}: {result.summary.get('non_finite', result.one_line)}")
    undetermined = result.summary.get("undetermined")
    if isinstance(undetermined, dict):
        _warn(
            f"{engine}: the model stops deciding the motion at t = "
            f"{undetermined.get('t_s', 0.0):.4f} s ({undetermined.get('detail', '')}); the "
            "history after it is one admissible outcome the rule chose"
        )
    return result


class Comparison(dict):
    """comparison.json as a dict (c["engines"]["bullet"]["verdict_kind"]), with .runs: every
    run's Result by engine name ("reference" first); .failures: the runs that failed; and
    .local_tolerance: each body's pointwise tolerance (docs/verdicts.md) on its grid,
    {"theta1": {"t": array (s), "tolerance_rad": array}}."""

    runs: dict
    failures: list
    local_tolerance: dict


def compare(
    scene,
    engines="all",
    members: int | None = None,
    engine_members: int | None = None,
    jobs: int = 0,
    progress: bool = True,
) -> Comparison:
    """Compares engines with the reference on a scene, as `rockbench compare SCENE`.

    engines:        "all" (every built engine) or a list of names (rockbench.engines()).
    members:        the reference's perturbation members (the predictability horizon); the
                    scene's compare.members (32) when None; 0: the pointwise comparison only
                    (the command line's --quick).
    engine_members: the engines' perturbation members beyond the horizon (compare.
                    engine_members, 16, when None).
    jobs:           threads for the members (0: every core), the command line's pool.
    progress:       print the command line's progress lines.

    Returns a Comparison: comparison.json's structure and keys, with .runs (each run's Result)
    and .failures. Warns (RockbenchWarning) for a failed run or engine and where the model
    stopped deciding the motion, as the command line does on stderr.
    """
    s = _as_scene(scene)
    overrides = []
    if members is not None:
        overrides.append(_override("compare.members", int(members)))
    if engine_members is not None:
        overrides.append(_override("compare.engine_members", int(engine_members)))
    if overrides:
        s = s.with_overrides(overrides)
    if isinstance(engines, str):
        text = engines
    else:
        text = ",".join(str(e) for e in engines)
    log = (lambda line: print(line, flush=True)) if progress else None
    d = _core.compare(s._core, text, int(jobs), log)
    if d["not_run_note"]:
        for line in d["not_run_note"].splitlines():
            _warn(line.removeprefix("rockbench: "))
    out = Comparison(json.loads(d["comparison_json"]))
    out.runs = {name: Result(r) for name, r in d["runs"].items()}
    out.failures = list(d["failures"])
    out.local_tolerance = {k: dict(v) for k, v in d["local_tolerance"].items()}
    for engine, reason in d["failed_engines"].items():
        _warn(f"compare failed: {engine}: {reason} (the other engines are compared)")
    for f in out.failures:
        _warn(f"compare failed: {f}")
    if d["undetermined_from_s"] is not None:
        _warn(
            f"reference: the model stops deciding the motion at t = "
            f"{d['undetermined_from_s']:.4f} s ({d['undetermined_detail']}); no engine is "
            "compared after it"
        )
    return out


def engines() -> list[dict]:
    """The engines of this build: [{"name", "built", "version", "reason", "brought_by"}], the
    reference first; an engine left out says why in "reason" (as `rockbench engines`)."""
    return list(_core.engines())


class _Progress:
    """A progress line on stderr, redrawn at most every 0.5 s ("ensemble: 12/64, 3.1 s")."""

    def __init__(self, label: str):
        self.label, self.start, self.last = label, time.monotonic(), -1.0

    def __call__(self, text: str) -> None:
        now = time.monotonic()
        done, _, total = text.partition("/")
        if now - self.last < 0.5 and done != total:
            return
        self.last = now
        sys.stderr.write(f"\r{self.label}: {text}, {now - self.start:.1f} s")
        if done == total:
            sys.stderr.write("\n")
        sys.stderr.flush()


def study(
    path,
    out,
    jobs: int = 0,
    resume: bool = False,
    keep_histories: bool = False,
    progress: bool = True,
):
    """Runs a study (docs/ensemble.md), as `rockbench ensemble STUDY --out OUT`: every member
    and engine in a worker process of the command line's pool (`jobs` workers, 0: every core),
    rows to OUT/members.csv as they finish, then the file in member order and OUT/study.json.
    `resume` goes on with OUT/members.csv. Ctrl-C ends the workers and raises
    KeyboardInterrupt; the rows written stay whole, for a resume.

    Returns read_study(out): members.csv as a pandas DataFrame.
    """
    callback = _Progress("ensemble") if progress else None
    notes = _core.run_study(
        os.fspath(path), os.fspath(out), int(jobs), bool(resume), bool(keep_histories), callback
    )
    for note in notes:
        _warn(note)
    return read_study(out)


def read_study(folder):
    """A finished (or resumable) study folder's members.csv as a pandas DataFrame, one row per
    (member, engine) (docs/ensemble.md for the columns). Needs pandas (python3-pandas)."""
    try:
        import pandas as pd
    except ImportError as e:
        raise ImportError("read_study needs pandas (Debian: python3-pandas)") from e
    path = os.path.join(os.fspath(folder), "members.csv")
    if not os.path.exists(path):
        raise ValueError(f"{path}: no such file (is {os.fspath(folder)} a study's --out folder?)")
    return pd.read_csv(path)
