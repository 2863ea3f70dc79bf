"""examples/notebook_api.py, the worked example of the Python API, runs top to bottom
in seconds and writes and prints what it says."""

import os
import subprocess
import sys
from pathlib import Path

import softimpact_cli as si

ROOT = Path(__file__).parents[1]
SCRIPT = ROOT / "examples" / "notebook_api.py"


def test_the_notebook_example_runs_and_its_outputs_agree(tmp_path):
    run = subprocess.run([sys.executable, str(SCRIPT), str(tmp_path)], capture_output=True,
                         text=True, timeout=600, cwd=tmp_path,
                         env={**os.environ, "MPLBACKEND": "Agg"})
    assert run.returncode == 0, run.stderr
    out = run.stdout
    assert f"kinds: {len(si.kinds())} (trajectory, catalogue, basins" in out
    assert "trajectory: converged, period" in out
    assert "catalogue: 2 attractors, 4 combinations" in out
    assert "basin shares: " in out and out.strip().endswith("basins.h5")
    png = tmp_path / "basins.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    stored = si.open_result(tmp_path / "basins.h5")
    assert stored.attrs["analysis"] == "basins" and stored["label"].shape[-2:] == (16, 16)
    # the shares it printed are those of the stored labels
    shares = out.split("basin shares: ")[1].splitlines()[0]
    names = dict(zip(stored["label_code"].values.tolist(),
                     stored["label_name"].values.tolist(), strict=True))
    label = stored["label"].values.ravel()
    for code in set(label.tolist()):
        assert f"{names[code]} {(label == code).mean():.2f}" in shares
    # the start's label is the one its trajectory converged to (same period)
    classify = out.split("classify: ")[1].splitlines()[0]
    period = int(out.split("trajectory: converged, period ")[1].split()[0])
    assert f"(period {period}) at d = 6" in classify
    assert "ci_low" in out and "ci_high" in out  # the shares' table
