"""``plot ... --dpi``: the resolution of the written raster."""

import struct

from click.testing import CliRunner

from softimpact_cli.cli import main
from softimpact_cli.store import write_result

from .test_trajectory_figure import trajectory


def png_width(path) -> int:
    with open(path, "rb") as f:
        head = f.read(24)
    return struct.unpack(">I", head[16:20])[0]


def test_dpi_sets_the_png_resolution(tmp_path):
    result = write_result(trajectory(-3.5, 0), tmp_path / "t.h5")
    widths = {}
    for dpi in (50, 100):
        out = tmp_path / f"t{dpi}.png"
        run = CliRunner().invoke(main, ["plot", "trajectory", str(result), "-o", str(out),
                                        "--dpi", str(dpi)])
        assert run.exit_code == 0, run.output
        widths[dpi] = png_width(out)
    assert abs(widths[100] - 2 * widths[50]) <= 2


def test_every_plot_subcommand_takes_dpi():
    for kind in ("trajectory", "basins", "dcrit", "stability", "bifurcation", "map",
                 "design", "catalogue"):
        run = CliRunner().invoke(main, ["plot", kind, "--help"])
        assert "--dpi" in run.output, kind
