"""fluidbed: a gas-fluidized bed of discrete particles and locally averaged gas (CFD-DEM).

The simulator of ``fluidbed`` (Xu & Yu 1997's bed and others) from Python: step a scene and read
its state as NumPy arrays, draw it, or call the command line's verbs and get their results back.

    import fluidbed
    sim = fluidbed.Simulation(fluidbed.scene("xu_yu_1997"), set={"inlet.superficial_velocity": 2.5})
    sim.run(until=0.2)
    print(sim.time, sim.dp, sim.particles.positions.shape)
    sim.save_png("bed.png", colour="force")

``help(fluidbed.Simulation)``, ``help(fluidbed.run)``; docs/python.md has the whole account.
"""

from __future__ import annotations

import codecs
import csv
import io
import json
import math
import os
import sys
import threading
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Dict, Iterable, List, Mapping, Optional, Sequence, Union

import numpy as np

# An installed copy (PREFIX/lib/python3*/*-packages/fluidbed) takes its scenes and font from
# PREFIX/share/fluidbed, as the installed program does; $FLUIDBED_ASSETS still wins, and the build
# tree's copy falls back to the source tree's assets.
_HERE = Path(__file__).resolve()  # PREFIX/lib/python3*/*-packages/fluidbed/__init__.py
_PREFIX = _HERE.parents[4] if len(_HERE.parents) > 4 else _HERE.parent
if "FLUIDBED_ASSETS" not in os.environ and (_PREFIX / "share" / "fluidbed" / "scenes").is_dir():
    os.environ["FLUIDBED_ASSETS"] = str(_PREFIX / "share" / "fluidbed")

from . import _core  # noqa: E402  (after the assets are known)

__all__ = [
    "Simulation", "Particles", "Gas", "RunResult", "SceneError", "SimulationError",
    "run", "sweep", "study", "keys", "scene", "scenes", "__version__",
]

__version__: str = _core.__version__

SceneError = _core.SceneError
SceneError.__doc__ = (
    "A bad scene, key, value or option: the command line's one-line error message (the program "
    "exits with status 2 on it).")
SimulationError = _core.SimulationError
SimulationError.__doc__ = (
    "The simulation blew up (NaN, runaway overlap, gas CFL number too large), in words, with what "
    "to try (the program exits with status 3 on it).")

PathLike = Union[str, "os.PathLike[str]"]


def _toml_value(value: Any) -> str:
    """A Python value as the TOML text --set takes: 2.5, true, "text", [[0.045, 0.045]]."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        v = float(value)
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(value, str):
        return value  # as on the command line: a bare word is taken as text
    if isinstance(value, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    raise SceneError(f"--set: cannot give {type(value).__name__} {value!r} as a scene value")


def _set_texts(set: Optional[Mapping[str, Any]]) -> List[str]:
    """{"section.key": value} as the command line's --set texts ("section.key=value")."""
    if set is None:
        return []
    if not isinstance(set, Mapping):
        raise SceneError("set= takes a dict of scene keys and values, e.g. "
                         "{'inlet.superficial_velocity': 2.5}")
    return [f"{key}={_toml_value(value)}" for key, value in set.items()]


def _list_text(values: Union[None, float, str, Iterable[float]]) -> str:
    """0.2 or [0.2, 0.4] or "0.2,0.4" as the command line's comma-separated list."""
    if values is None:
        return ""
    if isinstance(values, str):
        return values
    if isinstance(values, (int, float, np.integer, np.floating)):
        return repr(float(values))
    return ",".join(repr(float(v)) for v in values)


def _seeds_text(seeds: Union[None, int, Iterable[int]]) -> str:
    """--seeds: a count N, or a list of seeds."""
    if seeds is None:
        return ""
    if isinstance(seeds, (int, np.integer)):
        return str(int(seeds))
    return ",".join(str(int(s)) for s in seeds)


def scenes() -> List[str]:
    """The names of the scenes shipped with fluidbed (assets/scenes/NAME.toml)."""
    return sorted(p.stem for p in (Path(_core.asset_dir()) / "scenes").glob("*.toml"))


def scene(name: str) -> str:
    """The path of a shipped scene by name ("xu_yu_1997", "teaching", "drop", ...)."""
    path = Path(_core.asset_dir()) / "scenes" / f"{name}.toml"
    if not path.is_file():
        raise SceneError(f"no shipped scene named {name} (known: {', '.join(scenes())})")
    return str(path)


def keys() -> Dict[str, Dict[str, Any]]:
    """Every scene key, as ``fluidbed keys`` lists it: {"section.key": {"default", "unit",
    "range", "type", "help", "choices"}}. The default is TOML text ("50000.0", '"lattice"')."""
    return {k["key"]: {f: k[f] for f in ("default", "unit", "range", "type", "help", "choices")}
            for k in _core.keys()}


class Particles:
    """The particles at one instant, as NumPy arrays (copies: they stay as they are when the
    simulation steps on). Index i is particle id i.

    positions, velocities, forces: (N, 2) in a monolayer (x, y), (N, 3) in a thick slab (x, y, z);
    m, m/s, N (the total force: contacts, gravity, gas).
    spins, torques: (N,) about z in a monolayer; (N, 3) about x, y, z in a thick slab; rad/s, N m.
    radii: (N,) m. ids: (N,) int64.
    """

    def __init__(self, arrays: Dict[str, np.ndarray]):
        self.positions: np.ndarray = arrays["positions"]
        self.velocities: np.ndarray = arrays["velocities"]
        self.spins: np.ndarray = arrays["spins"]
        self.forces: np.ndarray = arrays["forces"]
        self.torques: np.ndarray = arrays["torques"]
        self.radii: np.ndarray = arrays["radii"]
        self.ids: np.ndarray = arrays["ids"]

    def __len__(self) -> int:
        return len(self.ids)

    def __repr__(self) -> str:
        return f"<fluidbed.Particles: {len(self)} particles>"


class Gas:
    """The gas at one instant on its grid, as (ny, nx) NumPy arrays at the cell centres (row j is
    height y[j], column i is x[i]; copies).

    u, v: interstitial velocity (m/s); p: pressure (Pa, relative to the outlet's);
    porosity: the void fraction the gas sees; x: (nx,) m; y: (ny,) m.
    """

    def __init__(self, arrays: Dict[str, np.ndarray]):
        self.u: np.ndarray = arrays["u"]
        self.v: np.ndarray = arrays["v"]
        self.p: np.ndarray = arrays["p"]
        self.porosity: np.ndarray = arrays["porosity"]
        self.x: np.ndarray = arrays["x"]
        self.y: np.ndarray = arrays["y"]

    @property
    def shape(self) -> tuple:
        """(ny, nx): cells up, cells across."""
        return self.u.shape

    def __repr__(self) -> str:
        return f"<fluidbed.Gas: {self.shape[1]} x {self.shape[0]} cells>"


def _look(colour: str, color: Optional[str], width: int, height: int, arrows: bool,
          bubbles: bool, close_up: float, dark: bool, porosity: bool, particle_arrows: bool,
          colour_range: Optional[Sequence[float]], backend: str) -> Any:
    look = _core.OutputArgs()
    look.colour = color if color is not None else colour
    look.frame_size = f"{int(width)}x{int(height)}"
    look.gas_arrows = bool(arrows)
    look.bubble_outlines = bool(bubbles)
    look.close_up = float(close_up)
    look.dark = bool(dark)
    look.porosity_background = bool(porosity)
    look.particle_arrows = bool(particle_arrows)
    look.colour_range = _list_text(colour_range)
    look.gl_backend = backend
    return look


def _native_figure(name: str, doc: str) -> property:
    """A read-only figure of the native simulation, as a property with its docstring."""
    return property(lambda self: getattr(self._sim, name), doc=doc)


class Simulation:
    """A scene stepped from Python, as ``fluidbed run`` steps it: the same start (the packed bed,
    cached as the command line caches it), the same steps, the same checks.

    Simulation(scene, set={"section.key": value}, threads=1)

    scene: a scene file (fluidbed.scene("xu_yu_1997") names a shipped one).
    set: scene values to change, as ``--set section.key=value`` (the same keys and checks; a bad
    one raises SceneError with the command line's message).
    threads: threads inside a step, as ``--threads`` (0: one per core).

    The state as NumPy copies: ``particles`` (Particles), ``gas`` (Gas, or None without gas),
    ``time``, ``dp``, ``state_hash``. The viewer's controls: ``superficial_velocity``,
    ``ideal_collisions``, ``reset()``. Pictures: ``render()``, ``save_png()``. Measurements:
    ``summary()``, ``energy()``, ``timeseries``, ``probes``, ``bubbles()``.

    The measurements cover the steps since the simulation was made, or since ``reset()`` or a
    switch of ``ideal_collisions`` (which replace the simulation); a change of
    ``superficial_velocity`` does not start them again.

    A blow-up raises SimulationError and leaves the state where it failed: ``reset()`` starts
    again.
    """

    def __init__(self, scene: PathLike, set: Optional[Mapping[str, Any]] = None,
                 threads: int = 1):
        self.scene = os.fspath(scene)
        self._sim = _core.Simulation(self.scene, _set_texts(set), int(threads))

    def step(self, n: int = 1) -> "Simulation":
        """Advances n particle time steps (time.dt each). The GIL is released while it steps;
        Ctrl+C (KeyboardInterrupt) stops it between two steps with the simulation usable."""
        self._sim.step(int(n))
        return self

    def run(self, until: Optional[float] = None, progress: bool = True) -> "Simulation":
        """Steps to simulated time ``until`` (s; None: the scene's time.end). With progress, a line
        on standard error says how far it is. The GIL is released while it steps; Ctrl+C
        (KeyboardInterrupt) stops it between two steps with the simulation usable."""
        end = self._sim.end_time if until is None else float(until)
        callback = None
        if progress:
            start = self._sim.time

            def callback(t: float) -> None:
                done = 100.0 if end <= start else 100.0 * (t - start) / (end - start)
                sys.stderr.write(f"\rt = {t:.4f} s of {end:.4g} s ({done:.0f} %)")
                sys.stderr.flush()

        try:
            self._sim.run(end, callback)
        finally:
            if progress:
                sys.stderr.write("\n")
        return self

    time = _native_figure("time", "Simulated time (s).")
    steps = _native_figure("steps", "Particle steps taken.")
    dt = _native_figure("dt", "The particle time step (s), time.dt.")
    dp = _native_figure("dp", "Pressure drop bottom to top on the symmetry line (Pa; 0 without "
                              "gas).")
    state_hash = _native_figure(
        "state_hash", "A 64-bit hash of the whole state (particles, contacts, gas): equal states, "
                      "equal hashes; `run` writes it into summary.json as 16 hex digits.")
    scene_toml = _native_figure(
        "scene_toml", "The scene as it runs, every value resolved (what `run` writes as "
                      "DIR/scene.toml).")

    @property
    def particles(self) -> Particles:
        """The particles now (Particles: NumPy copies)."""
        return Particles(self._sim.particles())

    @property
    def gas(self) -> Optional[Gas]:
        """The gas now (Gas: NumPy copies), or None for a scene without gas."""
        arrays = self._sim.gas()
        return None if arrays is None else Gas(arrays)

    @property
    def superficial_velocity(self) -> float:
        """The superficial gas velocity (m/s) from the next gas step on; set it as the viewer's
        slider does."""
        return self._sim.superficial_velocity

    @superficial_velocity.setter
    def superficial_velocity(self, u: float) -> None:
        self._sim.superficial_velocity = float(u)

    @property
    def ideal_collisions(self) -> bool:
        """The paper's ideal case: contact damping and friction 0 (the viewer's switch). Switching
        rebuilds the contact law and carries the state across bit for bit."""
        return self._sim.ideal_collisions

    @ideal_collisions.setter
    def ideal_collisions(self, on: bool) -> None:
        self._sim.ideal_collisions = bool(on)

    def bubbles(self) -> Dict[str, Any]:
        """The bubble analysis of the state now (the scene's [bubbles] settings, as
        ``run --bubbles`` analyses its frames): {"t": s, "regions": [...], "spout": bool,
        "median_speed": m/s, "surface": the bed surface per column of the analysis' grid (m)}.
        Each region: id, x, y (centroid, m), d_eq (m, sqrt(4 area / pi)), area (m^2), width,
        height (m), vx, vy (m/s, None until tracked), slug, jet_cavity. Calls in a row track
        the regions from one to the next (ids, velocities), as the run's frames do."""
        return self._sim.bubbles()

    def summary(self) -> Dict[str, Any]:
        """summary.json of the steps so far, as ``fluidbed run`` writes it for a run that ended
        here: dp_mean_pa (after diagnostics.averaging_start), max_overlap_ratio, the gas solver's
        statistics, bed_top_mean_m, probes, energy, the speed (wall time of the steps alone),
        state_hash, ..."""
        return json.loads(self._sim.summary())

    def energy(self) -> Dict[str, float]:
        """The particles' energy budget since the measurements started (summary()["energy"]):
        the mechanical energy's parts now (J), its change, the gas's work, the dashpots' and
        friction's dissipation, and the residual the step-by-step sums leave (J, per s, and as a
        share of the budget's largest term)."""
        return self.summary()["energy"]

    @property
    def timeseries(self) -> Any:
        """timeseries.csv of the steps so far, as ``fluidbed run`` writes it: a row every
        diagnostics.output_interval (t, dp, kinetic_energy, contacts, the energy budget's
        columns, bed_top, p_probe_N, ...), as columns (a pandas DataFrame when pandas is
        installed, else a dict of NumPy arrays)."""
        return _table(self._sim.timeseries())

    @property
    def probes(self) -> List[Dict[str, float]]:
        """The pressure probes of diagnostics.probes now: [{"x": m, "y": m, "p": Pa}, ...], p the
        gas pressure at the point minus the mean over the top row of cells (the timeseries'
        p_probe_N). Empty without probes."""
        values = self._sim.probes()
        return [{"x": x, "y": y, "p": p} for (x, y), p in zip(self._sim.probe_points, values)]

    def reset(self) -> "Simulation":
        """Back to the starting state (the same state hash as at the start)."""
        self._sim.reset()
        return self

    def render(self, colour: str = "speed", width: int = 1280, height: int = 720,
               arrows: bool = True, bubbles: bool = False, *, color: Optional[str] = None,
               close_up: float = 0.4, dark: bool = False, porosity: bool = False,
               particle_arrows: bool = False, colour_range: Optional[Sequence[float]] = None,
               backend: str = "osmesa") -> np.ndarray:
        """The state drawn as ``run --frames`` draws a frame: an (height, width, 3) uint8 RGB
        array, through the offscreen renderer.

        colour (or color): speed, force, torque, overlap, height, depth, fixed, as ``--colour``;
        arrows: gas velocity arrows (Fig. 14); bubbles: outlines of the bubbles and jet cavities;
        close_up: the lower fraction of the bed magnified beside it (0: none); porosity: the
        porosity field behind the particles; colour_range: (min, max) in the quantity's unit.
        """
        look = _look(colour, color, width, height, arrows, bubbles, close_up, dark, porosity,
                     particle_arrows, colour_range, backend)
        return self._sim.render(look)

    def save_png(self, path: PathLike, **render_options: Any) -> str:
        """Writes ``render(**render_options)`` to a PNG file; returns its path."""
        image = self.render(**render_options)
        _core.write_png(os.fspath(path), np.ascontiguousarray(image))
        return os.fspath(path)

    def __repr__(self) -> str:
        return (f"<fluidbed.Simulation {self._sim.scene_name}: t = {self.time:.6g} s, "
                f"{self.steps} steps>")


@dataclass
class RunResult:
    """What a verb wrote: its folder, summary.json as a dict and its table as columns (a pandas
    DataFrame when pandas is installed, else a dict of NumPy arrays)."""

    folder: str
    summary: Dict[str, Any]
    table: Any

    @property
    def timeseries(self) -> Any:
        """``run``'s timeseries.csv (the same as table)."""
        return self.table

    def read(self, name: str) -> Any:
        """Another CSV file of the folder as columns, e.g. ``read("bubbles.csv")`` after
        ``run(..., bubbles=True)``, ``read("dp_spectrum.csv")``; FileNotFoundError when the
        verb did not write it."""
        path = Path(self.folder) / name
        if not path.is_file():
            raise FileNotFoundError(f"{path}: not written by this run")
        return _read_table(path)


def _table(text: str) -> Any:
    """CSV text with a header row as columns: numbers as float arrays, anything else as text."""
    rows = list(csv.reader(io.StringIO(text)))
    if not rows:
        return None
    header, body = rows[0], rows[1:]
    columns: Dict[str, np.ndarray] = {}
    for k, name in enumerate(header):
        cells = [r[k] if k < len(r) else "" for r in body]
        try:
            columns[name] = np.array([float(c) if c != "" else math.nan for c in cells])
        except ValueError:
            columns[name] = np.array(cells, dtype=object)
    try:
        import pandas  # optional
    except ImportError:
        return columns
    return pandas.DataFrame(columns)


def _read_table(path: Path) -> Any:
    """A CSV file with a header row as columns (None when there is no such file)."""
    if not path.is_file():
        return None
    with open(path, newline="") as f:
        return _table(f.read())


def _read_json(path: Path) -> Dict[str, Any]:
    with open(path) as f:
        return json.load(f)


def _forward_output(fd: int, stream: Any) -> Any:
    """Points the process's file descriptor ``fd`` at a pipe whose text a thread writes to
    ``stream`` as it comes; returns a function that puts ``fd`` back and waits for the last text."""
    saved = os.dup(fd)
    read_end, write_end = os.pipe()
    os.dup2(write_end, fd)
    os.close(write_end)

    def pump() -> None:
        decoder = codecs.getincrementaldecoder("utf-8")(errors="replace")
        with os.fdopen(read_end, "rb", buffering=0) as pipe:
            for chunk in iter(lambda: pipe.read(4096), b""):
                stream.write(decoder.decode(chunk))
                stream.flush()

    thread = threading.Thread(target=pump, daemon=True)
    thread.start()

    def restore() -> None:
        os.dup2(saved, fd)  # the pipe's last writer gone: the thread reads to its end
        os.close(saved)
        thread.join()

    return restore


def _process_streams() -> bool:
    """True when sys.stdout and sys.stderr are the process's own (a terminal, a script), false
    where Python has its own (a Jupyter kernel's streams to the notebook)."""
    try:
        return sys.stdout.fileno() == 1 and sys.stderr.fileno() == 2
    except (AttributeError, OSError, ValueError):
        return False


def _call_verb(verb: Any, args: Any) -> int:
    """A verb of the command line. What it prints reaches sys.stdout and sys.stderr while it runs
    where those are not the process's own (Jupyter shows it under the cell), all of it before
    the verb returns, so that it is not mixed into what the caller prints next."""
    if _process_streams():
        return verb(args)
    sys.stdout.flush()
    sys.stderr.flush()
    restore = [_forward_output(1, sys.stdout), _forward_output(2, sys.stderr)]
    try:
        return verb(args)
    finally:
        _core.flush_output()
        for r in restore:
            r()


def _verb_status(status: int, what: str, resume: str) -> None:
    if status == 130:
        raise KeyboardInterrupt(f"{what} interrupted; resume with: {resume}")
    if status != 0:
        raise RuntimeError(f"{what} ended with status {status}")


def run(scene: PathLike, until: Optional[float] = None, out: Optional[PathLike] = None,
        set: Optional[Mapping[str, Any]] = None, frames: bool = False, video: bool = False,
        vtk: bool = False, montage: Union[None, float, Sequence[float]] = None,
        plots: bool = False, bubbles: bool = False,
        seeds: Union[None, int, Sequence[int]] = None, threads: int = 1,
        colour: Optional[str] = None, color: Optional[str] = None,
        frame_size: Optional[str] = None, resume: bool = False) -> RunResult:
    """``fluidbed run``: the scene to ``until`` (s; None: its time.end) into folder ``out``
    (None: out/<scene name>), writing the same files as the command line; returns the summary and
    the timeseries. frames, video, vtk, montage (times in s), plots, bubbles, seeds (a count or a
    list: an ensemble over packings), colour and frame_size ("1280x720") are the command line's
    options. resume=True finishes the interrupted run in ``out``. Ctrl+C stops the run with a
    checkpoint (KeyboardInterrupt); run(..., resume=True) goes on from there."""
    a = _core.RunArgs()
    folder = os.fspath(out) if out is not None else os.path.join("out", Path(scene).stem)
    a.out = folder
    given: List[str] = []
    if resume:
        a.resume = folder
    else:
        a.scene = os.fspath(scene)
        a.overrides = _set_texts(set)
        a.until = -1.0 if until is None else float(until)
        a.seeds = _seeds_text(seeds)
    a.threads = int(threads)
    a.threads_given = threads != 1
    o = a.output
    o.frames, o.video, o.vtk = bool(frames), bool(video), bool(vtk)
    o.montage = _list_text(montage)
    a.plots, a.bubbles = bool(plots), bool(bubbles)
    if color is not None or colour is not None:
        o.colour = color if color is not None else colour
        given.append("colour")
    if frame_size is not None:
        o.frame_size = frame_size
        given.append("frame_size")
    for name, on in (("frames", frames), ("video", video), ("vtk", vtk),
                     ("montage", montage is not None), ("plots", plots), ("bubbles", bubbles)):
        if on:
            given.append(name)
    a.output = o
    a.outputs_given = given
    _verb_status(_call_verb(_core.run_command, a), "run", f"fluidbed.run(..., out={folder!r}, resume=True)")
    d = Path(folder)
    return RunResult(folder, _read_json(d / "summary.json"), _read_table(d / "timeseries.csv"))


def sweep(scene: Optional[PathLike] = None, velocities: Union[None, Sequence[float]] = None,
          run_time: float = 1.5, averaging_start: float = 0.5, out: Optional[PathLike] = None,
          set: Optional[Mapping[str, Any]] = None,
          seeds: Union[None, int, Sequence[int]] = None, threads: int = 2,
          resume: bool = False) -> RunResult:
    """``fluidbed sweep``: the velocity sweep up and back down (the paper's Fig. 6) and U_mf, into
    ``out`` (None: out/sweep); returns summary.json and sweep.csv's columns. velocities in m/s
    (None: the paper's 23, scaled to the scene), run_time and averaging_start in s per velocity,
    threads: runs side by side. resume=True finishes the interrupted sweep in ``out``."""
    a = _core.SweepArgs()
    folder = os.fspath(out) if out is not None else os.path.join("out", "sweep")
    a.out = folder
    if resume:
        a.resume = folder
    else:
        a.scene = "" if scene is None else os.fspath(scene)
        a.overrides = _set_texts(set)
        a.velocities = _list_text(velocities)
        a.run_time = float(run_time)
        a.averaging_start = float(averaging_start)
        a.seeds = _seeds_text(seeds)
        a.options_given = True
    a.threads = int(threads)
    a.threads_given = threads != 2
    _verb_status(_call_verb(_core.sweep_command, a), "sweep",
                 f"fluidbed.sweep(out={folder!r}, resume=True)")
    d = Path(folder)
    return RunResult(folder, _read_json(d / "summary.json"), _read_table(d / "sweep.csv"))


def study(name: str, out: Optional[PathLike] = None, size: str = "full",
          scene: Optional[PathLike] = None, vary: Union[None, str, Sequence[str]] = None,
          set: Optional[Mapping[str, Any]] = None, until: float = 0.0,
          seeds: Union[None, int, Sequence[int]] = None, jobs: int = 0,
          resume: bool = False) -> RunResult:
    """``fluidbed study NAME``: a study of speed against accuracy or of a scene's sensitivity,
    into ``out`` (None: out/study-NAME); returns study.csv's columns (summary: its status.json).
    size: "full" or "tiny"; for "sensitivity": scene, vary ("key=v1,v2" texts as --vary), set,
    until (s; 0: the scene's) and seeds. resume=True finishes the interrupted study in ``out``."""
    a = _core.StudyArgs()
    folder = os.fspath(out) if out is not None else os.path.join("out", f"study-{name}")
    a.name = name
    a.out = folder
    if resume:
        a.resume = folder
    a.size = size
    a.scene = "" if scene is None else os.fspath(scene)
    a.vary = [] if vary is None else ([vary] if isinstance(vary, str) else list(vary))
    a.overrides = _set_texts(set)
    a.until = float(until)
    a.seeds = _seeds_text(seeds)
    a.jobs = int(jobs)
    _verb_status(_call_verb(_core.study_command, a), "study",
                 f"fluidbed.study({name!r}, out={folder!r}, resume=True)")
    d = Path(folder)
    status = d / "status.json"
    return RunResult(folder, _read_json(status) if status.is_file() else {},
                     _read_table(d / "study.csv"))
