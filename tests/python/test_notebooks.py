"""The lessons shipped in assets/notebooks run top to bottom (Debian's python3-nbclient), shortened
by their cell tagged "parameters", and are kept in the repository without outputs.

Run by ctest (test Python.Notebooks) with PYTHONPATH at the build tree's package (the kernel
inherits it) and FLUIDBED_CACHE the tests' packed beds.
"""

import json
from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

import fluidbed

NOTEBOOKS = Path(__file__).resolve().parents[2] / "assets" / "notebooks"

# Each lesson's settings for a test: the same cells, a fraction of the simulated time.
QUICK = {
    "find_umf.ipynb": """
velocities = [1.0, 2.6]
run_time = 0.3
averaging_start = 0.1
look_time = 0.05
threads = 1
""",
    "bubbles.ipynb": """
until = 1.2
frame_times = [0.35, 0.4]
threads = 1
""",
}


def parameters_cell(nb):
    cells = [c for c in nb.cells if "parameters" in c.metadata.get("tags", [])]
    assert len(cells) == 1, "one cell tagged parameters"
    return cells[0]


def test_every_lesson_is_tested_and_installed_with_the_assets():
    assert {p.name for p in NOTEBOOKS.glob("*.ipynb")} == set(QUICK)
    assert (Path(fluidbed._core.asset_dir()) / "notebooks").is_dir()


@pytest.mark.parametrize("name", sorted(QUICK))
def test_a_lesson_is_kept_without_outputs(name):
    nb = nbformat.read(NOTEBOOKS / name, as_version=4)
    nbformat.validate(nb)
    for cell in nb.cells:
        if cell.cell_type == "code":
            assert cell.outputs == [] and cell.execution_count is None, cell.source[:60]


def run_lesson(name, folder):
    nb = nbformat.read(NOTEBOOKS / name, as_version=4)
    cell = parameters_cell(nb)
    # The quick values replace the lesson's, names for names.
    names = {line.split("=")[0].strip() for line in cell.source.splitlines()
             if "=" in line and not line.startswith("#")}
    quick = QUICK[name].strip()
    assert {line.split("=")[0].strip() for line in quick.splitlines()} == names
    cell.source = quick
    NotebookClient(nb, timeout=600, kernel_name="python3",
                   resources={"metadata": {"path": str(folder)}}).execute()
    return nb


def outputs(nb):
    """Every output of every code cell: (text, number of PNG pictures)."""
    text, pictures = [], 0
    for cell in nb.cells:
        for out in cell.get("outputs", []):
            if out.output_type == "stream":
                text.append(out.text)
            elif "data" in out:
                text.append(out.data.get("text/plain", ""))
                pictures += "image/png" in out.data
    return "".join(text), pictures


def test_find_umf_runs_top_to_bottom(tmp_path):
    nb = run_lesson("find_umf.ipynb", tmp_path)
    text, pictures = outputs(nb)
    assert pictures == 2  # the bed below and above U_mf; dp against U
    assert "bed weight per area:" in text and "Ergun:  U_mf" in text and "Wen-Yu: U_mf" in text
    assert "U_mf from the decreasing branch:" in text
    # The verb's own lines reach the notebook, all before the cell prints on.
    assert text.index("wrote lesson-umf/sweep.csv") < text.index("\nU_mf from the decreasing")
    # The sweep the cells ran is the one the parameters asked for, in the lesson's folder.
    rows = (tmp_path / "lesson-umf" / "sweep.csv").read_text().splitlines()
    assert rows[0].startswith("branch,u_superficial,dp_mean") and len(rows) == 1 + 3  # up 2, down 1
    summary = json.loads((tmp_path / "lesson-umf" / "summary.json").read_text())
    # The bed weight the notebook worked out is the program's (summary.json's, Pa).
    line = next(s for s in text.splitlines() if s.startswith("bed weight per area:"))
    assert abs(float(line.split()[-2]) - summary["bed_weight_per_area_pa"]) <= 0.5


def test_bubbles_runs_top_to_bottom(tmp_path):
    nb = run_lesson("bubbles.ipynb", tmp_path)
    text, pictures = outputs(nb)
    assert pictures == 3  # the frames, size against height, rise velocity
    assert "regime:" in text and "mean rise velocity:" in text
    assert "wrote lesson-bubbles/bubbles.csv" in text  # the verb's own lines reach the notebook
    assert (tmp_path / "lesson-bubbles" / "bubbles.csv").is_file()
