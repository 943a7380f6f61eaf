"""`import fluidbed` against the command line: the same states, messages, pictures and files.

Run by ctest (test Python.Module) with PYTHONPATH at the build tree's package, FLUIDBED_PROGRAM
the `fluidbed` program of the same build and FLUIDBED_CACHE the tests' packed beds.
"""

import ast
import json
import math
import os
import signal
import struct
import subprocess
import threading
import time
import zlib
from pathlib import Path

import numpy as np
import pytest

import fluidbed

PROGRAM = os.environ.get("FLUIDBED_PROGRAM", "fluidbed")
PAPER = fluidbed.scene("xu_yu_1997")
DROP = fluidbed.scene("drop")


def cli(*args, check=True):
    """The program with these arguments: (status, stdout, stderr)."""
    p = subprocess.run([PROGRAM, *map(str, args)], capture_output=True, text=True)
    if check and p.returncode != 0:
        raise AssertionError(f"fluidbed {' '.join(map(str, args))}: {p.returncode}\n{p.stderr}")
    return p.returncode, p.stdout, p.stderr


def read_png(path):
    """The (height, width, 3) pixels of an RGB PNG as the program writes it (unfiltered rows)."""
    data = Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, width, height, idat = 8, 0, 0, b""
    while pos < len(data):
        size, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + size]
        if kind == b"IHDR":
            width, height = struct.unpack(">II", body[:8])
        elif kind == b"IDAT":
            idat += body
        pos += 12 + size
    raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(height, width * 3 + 1)
    assert (raw[:, 0] == 0).all(), "a row with a filter"
    return raw[:, 1:].reshape(height, width, 3)


def rss_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def test_the_stubs_name_what_the_module_has():
    stub = ast.parse((Path(fluidbed.__file__).parent / "__init__.pyi").read_text())
    stub_top, stub_members = set(), {}
    for node in stub.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            stub_top.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            stub_top.add(node.target.id)
        if isinstance(node, ast.ClassDef):
            stub_members[node.name] = {
                n.name if isinstance(n, ast.FunctionDef) else n.target.id
                for n in node.body if isinstance(n, (ast.FunctionDef, ast.AnnAssign))}
    assert stub_top - {"PathLike"} == set(fluidbed.__all__)
    for name, members in stub_members.items():
        cls = getattr(fluidbed, name)
        public = {m for m in vars(cls) if not m.startswith("_") or m in ("__init__", "__len__")}
        if name == "Simulation":  # instance attributes set by __init__
            public |= {"scene"}
        if name in ("Particles", "Gas", "RunResult"):
            public |= set(cls.__init__.__code__.co_names) & members
            public |= set(getattr(cls, "__annotations__", {}))
        extra = members - public - {"__init__", "__len__"}
        missing = {m for m in public if not m.startswith("_")} - members
        assert not extra and not missing, (name, extra, missing)


def test_every_public_function_has_a_docstring():
    for name in fluidbed.__all__:
        obj = getattr(fluidbed, name)
        if callable(obj):
            assert obj.__doc__ and len(obj.__doc__) > 20, name
    for name, member in vars(fluidbed.Simulation).items():
        if not name.startswith("_"):
            assert member.__doc__, f"Simulation.{name}"


def test_a_bad_key_raises_the_command_lines_message():
    status, _, err = cli("run", DROP, "--set", "particles.densty=3", "--until", "0", check=False)
    assert status == 2
    with pytest.raises(fluidbed.SceneError) as e:
        fluidbed.Simulation(DROP, set={"particles.densty": 3})
    assert err.strip() == "fluidbed: error: " + str(e.value)
    with pytest.raises(fluidbed.SceneError) as e:
        fluidbed.Simulation(DROP, set={"particles.density": -1.0})
    status, _, err = cli("run", DROP, "--set", "particles.density=-1.0", "--until", "0",
                         check=False)
    assert status == 2 and err.strip() == "fluidbed: error: " + str(e.value)


def test_the_state_after_the_same_steps_is_the_command_lines(tmp_path):
    cli("run", PAPER, "--until", "0.01", "--out", tmp_path / "cli")
    summary = json.loads((tmp_path / "cli" / "summary.json").read_text())
    sim = fluidbed.Simulation(PAPER)
    sim.run(until=0.01, progress=False)
    assert sim.steps == summary["steps"]
    assert f"{sim.state_hash:016x}" == summary["state_hash"]
    p, g = sim.particles, sim.gas
    assert p.positions.shape == (2400, 2) and p.spins.shape == (2400,)
    assert np.allclose(2 * p.radii, 0.004)
    assert g.u.shape == (len(g.y), len(g.x)) == g.shape
    assert sim.dp > 0.0  # the gas pushes through the bed
    # Copies: the arrays stay as they were when the simulation steps on.
    before = p.positions.copy()
    sim.step(50)
    assert np.array_equal(p.positions, before)
    assert not np.array_equal(sim.particles.positions, before)


def test_a_thick_slab_has_three_components():
    sim = fluidbed.Simulation(DROP, set={"domain.thickness": 0.012})
    sim.step(10)
    p = sim.particles
    assert p.positions.shape == (1, 3) and p.velocities.shape == (1, 3)
    assert p.spins.shape == (1, 3) and p.torques.shape == (1, 3)
    assert sim.gas is None


def test_render_gives_the_command_lines_frame(tmp_path):
    cli("run", PAPER, "--until", "0.01", "--frames", "--frame-interval", "0.01", "--colour",
        "force", "--out", tmp_path / "cli")
    sim = fluidbed.Simulation(PAPER)
    sim.run(until=0.01, progress=False)
    image = sim.render(colour="force")
    assert image.shape == (720, 1280, 3) and image.dtype == np.uint8
    frame = read_png(tmp_path / "cli" / "frames" / "frame_000001.png")
    assert np.array_equal(image, frame)
    sim.save_png(tmp_path / "py.png", color="force")
    assert (tmp_path / "py.png").read_bytes() == \
        (tmp_path / "cli" / "frames" / "frame_000001.png").read_bytes()
    small = sim.render(width=320, height=240, arrows=False, bubbles=True)
    assert small.shape == (240, 320, 3)
    with pytest.raises(fluidbed.SceneError):
        sim.render(colour="purple")


def test_bubbles_are_the_ones_the_run_finds(tmp_path):
    cli("run", PAPER, "--until", "0.2", "--bubbles", "--out", tmp_path / "cli")
    rows = (tmp_path / "cli" / "bubbles.csv").read_text().splitlines()
    header = rows[0].split(",")
    rows = [dict(zip(header, r.split(","))) for r in rows[1:]]
    t = max(float(r["t"]) for r in rows)
    # The regions of the last frame with bubbles (rows of bubbles that ended there are not).
    want = sorted((float(r["x"]), float(r["y"]), float(r["d_eq"])) for r in rows
                  if float(r["t"]) == t and r["event"] not in ("erupted", "vanished"))
    assert want, "no bubble in the frame"
    sim = fluidbed.Simulation(PAPER)
    sim.run(until=t, progress=False)
    found = sim.bubbles()
    assert abs(found["t"] - t) < 1e-9
    got = sorted((b["x"], b["y"], b["d_eq"]) for b in found["regions"] if not b["jet_cavity"])
    assert np.allclose(got, want, rtol=1e-8, atol=0)
    # A picture with outlines of the same state shares its frame; a reset starts the tracking
    # again.
    sim.render(width=320, height=240, bubbles=True)
    assert sim.bubbles()["regions"] == found["regions"]
    sim.reset()
    sim.run(until=0.1, progress=False)
    assert sim.bubbles()["t"] == sim.time


def test_run_gives_the_command_lines_summary_and_timeseries(tmp_path):
    cli("run", DROP, "--until", "0.2", "--out", tmp_path / "cli")
    r = fluidbed.run(DROP, until=0.2, out=tmp_path / "py")
    want = json.loads((tmp_path / "cli" / "summary.json").read_text())
    assert set(r.summary) == set(want)
    for key in want:
        if "wall" not in key and "per_s" not in key and "cpu" not in key:
            assert r.summary[key] == want[key], key
    cli_rows = (tmp_path / "cli" / "timeseries.csv").read_text().splitlines()
    columns = r.timeseries
    assert list(columns.keys()) == cli_rows[0].split(",")
    assert len(columns["t"]) == len(cli_rows) - 1
    assert np.array_equal(np.asarray(columns["t"]),
                          [float(line.split(",")[0]) for line in cli_rows[1:]])
    assert (tmp_path / "py" / "scene.toml").read_text() == \
        (tmp_path / "cli" / "scene.toml").read_text()


def test_keys_are_the_command_lines():
    keys = fluidbed.keys()
    _, text, _ = cli("keys")
    listed = {line.split()[0] for line in text.splitlines()[1:] if line.strip()}
    assert set(keys) == listed
    d = keys["particles.density"]
    assert d["unit"] == "kg/m^3" and d["range"] == "> 0" and float(d["default"]) > 0


def send_sigint_after(seconds):
    """SIGINT to this process from another process (it needs no GIL of ours to fire)."""
    return subprocess.Popen(["sh", "-c", f"sleep {seconds}; kill -INT {os.getpid()}"])


def test_ctrl_c_stops_a_run_and_leaves_the_simulation_usable():
    sim = fluidbed.Simulation(PAPER)
    killer = send_sigint_after(0.3)
    with pytest.raises(KeyboardInterrupt):
        sim.run(until=2.0, progress=False)
    killer.wait()
    stopped = sim.steps
    assert 0 < stopped < round(2.0 / sim.dt)
    sim.step(20)
    # The state is the one of an unbroken run of as many steps.
    again = fluidbed.Simulation(PAPER)
    again.step(stopped + 20)
    assert again.state_hash == sim.state_hash


def test_ctrl_c_stops_the_run_verb_with_a_checkpoint_and_resume_finishes_it(tmp_path):
    killer = send_sigint_after(0.7)
    with pytest.raises(KeyboardInterrupt):
        fluidbed.run(PAPER, until=0.3, out=tmp_path / "run")
    killer.wait()
    status = json.loads((tmp_path / "run" / "status.json").read_text())
    assert status["status"] == "interrupted" and 0 < status["t_s"] < 0.3
    r = fluidbed.run(PAPER, out=tmp_path / "run", resume=True)
    sim = fluidbed.Simulation(PAPER)
    sim.run(until=0.3, progress=False)
    assert r.summary["state_hash"] == f"{sim.state_hash:016x}"


def test_the_gil_is_released_while_it_steps():
    # A second thread wakes every 5 ms and counts; each count needs the GIL. While the engine
    # steps with the GIL released it keeps counting; were it held, the thread could not.
    sim = fluidbed.Simulation(PAPER)
    count = [0]
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            time.sleep(0.005)
            count[0] += 1

    t = threading.Thread(target=tick)
    t.start()
    time.sleep(0.05)
    before = count[0]
    start = time.monotonic()
    sim.step(2000)
    spent = time.monotonic() - start
    during = count[0] - before
    stop.set()
    t.join()
    assert spent > 0.2, "too few steps to tell"
    assert during >= 0.3 * spent / 0.005, f"{during} wake-ups in {spent:.2f} s of stepping"


def test_the_viewers_controls():
    sim = fluidbed.Simulation(PAPER)
    start = sim.state_hash
    sim.superficial_velocity = 2.5
    assert sim.superficial_velocity == 2.5
    sim.ideal_collisions = True
    assert sim.ideal_collisions
    sim.step(20)
    sim.reset()
    assert sim.time == 0.0 and sim.ideal_collisions
    sim.ideal_collisions = False
    sim.reset()
    assert sim.state_hash == start
    with pytest.raises(fluidbed.SceneError):
        sim.superficial_velocity = -1.0


def test_a_blow_up_raises_in_words_and_reset_starts_again():
    sim = fluidbed.Simulation(PAPER)
    start = sim.state_hash
    sim.superficial_velocity = 300.0
    with pytest.raises(fluidbed.SimulationError, match="CFL number") as e:
        sim.run(until=0.05, progress=False)
    # The likely cause names the velocity in use, not the scene's.
    assert "300 m/s superficial in use; the scene's inlet.superficial_velocity is 2.8 m/s" \
        in str(e.value)
    sim.reset()
    assert sim.state_hash == start and sim.time == 0.0


@pytest.mark.skipif(os.environ.get("FLUIDBED_SANITIZED") == "1",
                    reason="under ASan freed memory waits in quarantine; LeakSanitizer checks")
def test_no_leak_over_a_thousand_simulations():
    def cycle():
        sim = fluidbed.Simulation(DROP)
        sim.step(10)
        _ = sim.particles.positions
        del sim

    for _ in range(100):
        cycle()
    before = rss_bytes()
    for _ in range(1000):
        cycle()
    after = rss_bytes()
    assert after <= 1.05 * before, f"RSS {before / 2**20:.1f} -> {after / 2**20:.1f} MiB"


def test_the_measurements_of_a_simulation_are_the_command_lines(tmp_path):
    probe = {"diagnostics.probes": [[0.075, 0.05]]}
    cli("run", PAPER, "--until", "0.05", "--set", "diagnostics.probes=[[0.075, 0.05]]", "--out",
        tmp_path / "cli")
    sim = fluidbed.Simulation(PAPER, set=probe)
    sim.run(until=0.05, progress=False)
    want = json.loads((tmp_path / "cli" / "summary.json").read_text())
    got = sim.summary()
    # The recorder's keys are the run's; the run adds what the verb knows (scene, version, ...).
    assert set(got) <= set(want) and {"dp_mean_pa", "energy", "probes"} <= set(got)
    for key in got:
        if "wall" not in key and "per_s" not in key and "cpu" not in key:
            assert got[key] == want[key], key
    assert sim.energy() == got["energy"]
    e = got["energy"]  # the budget closes: change = work - losses + residual
    assert abs(e["mechanical_change_j"] - (e["gas_work_j"] - e["dashpot_dissipation_j"]
                                           - e["friction_dissipation_j"] + e["residual_j"])) \
        <= 1e-9 * max(abs(e["gas_work_j"]), 1e-12)
    rows = (tmp_path / "cli" / "timeseries.csv").read_text().splitlines()
    columns = sim.timeseries
    assert list(columns.keys()) == rows[0].split(",") and "p_probe_1" in columns
    # A row every output interval; the run adds one at its last step, which is not on one.
    assert len(columns["t"]) == len(rows) - 2
    assert float(rows[-1].split(",")[0]) == pytest.approx(sim.time, abs=1e-12)
    for k, name in enumerate(rows[0].split(",")):
        assert np.array_equal(np.asarray(columns[name]),
                              [float(line.split(",")[k]) for line in rows[1:-1]]), name
    (point,) = sim.probes
    assert (point["x"], point["y"]) == (0.075, 0.05)
    assert point["p"] == pytest.approx(float(rows[-1].split(",")[-1]), rel=1e-8)
    # reset() starts the measurements afresh; a velocity change does not.
    sim.superficial_velocity = 2.0
    assert len(sim.timeseries["t"]) == len(rows) - 2
    sim.reset()
    assert len(sim.timeseries["t"]) == 0 and sim.summary()["steps"] == 0


def test_study_gives_the_command_lines_table(tmp_path):
    cli("study", "energy", "--size", "tiny", "--jobs", "1", "--out", tmp_path / "cli")
    r = fluidbed.study("energy", size="tiny", jobs=1, out=tmp_path / "py")
    text = (tmp_path / "cli" / "study.csv").read_text().splitlines()
    header = text[0].split(",")
    assert list(r.table.keys()) == header and len(r.table[header[0]]) == len(text) - 1
    for k, name in enumerate(header):
        if "wall" in name or "per_s" in name or "cpu" in name:
            continue
        want = [line.split(",")[k] for line in text[1:]]
        for w, g in zip(want, list(r.table[name])):
            if w == "":  # an empty cell: NaN in a column of numbers
                assert g == "" or math.isnan(g), name
            elif isinstance(g, str):
                assert w == g, name
            else:
                assert float(w) == g, name
    assert r.summary.get("status") == "completed"
