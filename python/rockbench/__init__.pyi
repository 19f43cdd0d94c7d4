# Type hints of the rockbench package (docs/python.md).
import os
from collections.abc import Iterator, Mapping, Sequence
from typing import Any, Literal

import numpy as np
import numpy.typing as npt

__version__: str

class RockbenchWarning(UserWarning): ...

_PathOrText = str | os.PathLike[str]

class Scene:
    @classmethod
    def from_toml(cls, path_or_text: _PathOrText, overrides: Sequence[str] = ...) -> Scene: ...
    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> Scene: ...
    def to_dict(self) -> dict[str, Any]: ...
    def to_toml(self) -> str: ...
    def with_overrides(self, overrides: Sequence[str]) -> Scene: ...
    @property
    def path(self) -> str: ...
    @property
    def blocks(self) -> int: ...
    @property
    def title(self) -> str: ...
    @property
    def duration_s(self) -> float: ...

_SceneLike = Scene | Mapping[str, Any] | _PathOrText

class History(Mapping[str, npt.NDArray[np.float64] | list[str]]):
    def __getitem__(self, name: str) -> Any: ...
    def __iter__(self) -> Iterator[str]: ...
    def __len__(self) -> int: ...
    @property
    def columns(self) -> list[str]: ...
    @property
    def samples(self) -> int: ...
    def to_pandas(self) -> Any: ...

class Result:
    engine: str
    status: str
    history: History
    events: History
    summary: dict[str, Any]
    one_line: str
    wall_s: float
    core_s: float
    def history_csv(self) -> str: ...
    def events_csv(self) -> str: ...
    def save(self, out_dir: str | os.PathLike[str]) -> None: ...

class Comparison(dict[str, Any]):
    runs: dict[str, Result]
    failures: list[str]
    local_tolerance: dict[str, dict[str, npt.NDArray[np.float64]]]

def run(scene: _SceneLike, engine: str = "reference", **settings: Any) -> Result: ...
def compare(
    scene: _SceneLike,
    engines: Literal["all"] | str | Sequence[str] = "all",
    members: int | None = None,
    engine_members: int | None = None,
    jobs: int = 0,
    progress: bool = True,
) -> Comparison: ...
def engines() -> list[dict[str, Any]]: ...
def study(
    path: str | os.PathLike[str],
    out: str | os.PathLike[str],
    jobs: int = 0,
    resume: bool = False,
    keep_histories: bool = False,
    progress: bool = True,
) -> Any: ...
def read_study(folder: str | os.PathLike[str]) -> Any: ...
