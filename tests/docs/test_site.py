"""The documentation site builds offline and in strict mode (what `make docs` runs): every
page, the generated references, the executed tutorials; and a broken link fails it."""

import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytest.importorskip("mkdocs", reason="the docs extra: pip install -e '.[docs]' (make install)")

ROOT = Path(__file__).parents[2]
ENV = {**os.environ, "NO_MKDOCS_2_WARNING": "1", "MPLBACKEND": "Agg"}


def build(config: Path, site: Path, execute: bool = True) -> subprocess.CompletedProcess:
    env = {**ENV, "SOFTIMPACT_DOCS_EXECUTE": "1" if execute else "0"}
    return subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-f",
                           str(config), "-d", str(site)], cwd=config.parent, env=env,
                          capture_output=True, text=True, timeout=1800)


@pytest.mark.slow
def test_the_site_builds_strict_with_every_page_and_tutorial(tmp_path):
    site = tmp_path / "site"
    started = time.perf_counter()
    run = build(ROOT / "mkdocs.yml", site)
    wall = time.perf_counter() - started
    assert run.returncode == 0, run.stderr[-3000:]
    pages = sorted(p.relative_to(site).as_posix() for p in site.rglob("*.html"))
    print(f"site: {len(pages)} pages in {wall:.0f} s")
    for page in ("index.html", "getting-started.html", "reference/scene-keys.html",
                 "reference/api.html", "reference/commands.html", "gallery.html",
                 "howto/reproduce-table.html", "validation/numerics.html"):
        assert page in pages
    tutorials = sorted((ROOT / "docs" / "tutorials").glob("*.py"))
    assert len(tutorials) >= 9
    assert "own_model" in {path.stem for path in tutorials}
    for path in tutorials:
        html = (site / "tutorials" / f"{path.stem}.html").read_text()
        assert "Executed when the site was built" in html, path.name
        if path.stem != "batch_ci":  # the others draw their results
            assert f'src="{path.stem}-1.png"' in html, f"{path.name} shows no figure"
            assert (site / "tutorials" / f"{path.stem}-1.png").stat().st_size > 5000
    own = (site / "tutorials" / "own_model.html").read_text()
    assert "bodies 1..3" in own and "exit status: 2" in own  # the bad stop's one line
    assert "stop 3 (body 3 / right wall)" in own  # the chain ran, each stop measured
    api = (site / "reference" / "api.html").read_text()
    assert 'id="softimpact_cli.api.sweep"' in api  # mkdocstrings rendered the module
    keys = (site / "reference" / "scene-keys.html").read_text()
    assert "steps_per_period" in keys and "section_zero_exponent" in keys
    gallery = (site / "gallery.html").read_text()
    for png in (ROOT / "docs" / "gallery").glob("*.png"):
        assert f"gallery/{png.name}" in gallery, f"gallery.md does not show {png.name}"


def test_a_broken_link_fails_the_build(tmp_path):
    """The site in a scratch copy (tutorials rendered, not run) with one link to a page that
    does not exist: the strict build fails on that link alone (the whole site builds in
    the test above)."""
    for name in ("docs", "configs"):
        shutil.copytree(ROOT / name, tmp_path / name)
    (tmp_path / "results").mkdir()
    shutil.copy(ROOT / "results" / "reproduce.md", tmp_path / "results")
    shutil.copy(ROOT / "mkdocs.yml", tmp_path)
    page = tmp_path / "docs" / "citing.md"
    page.write_text(page.read_text() + "\nSee [the numerics](validation/numerik.md).\n")
    broken = build(tmp_path / "mkdocs.yml", tmp_path / "site", execute=False)
    assert broken.returncode != 0
    assert "validation/numerik.md" in broken.stderr
    warnings = [line for line in broken.stderr.splitlines() if line.startswith("WARNING")]
    assert len(warnings) == 1, broken.stderr[-3000:]


def gallery_copies(*args: str) -> set[str]:
    """The PNGs `make -n ARGS` would copy into docs/gallery/."""
    run = subprocess.run(["make", "-n", *args], cwd=ROOT, capture_output=True, text=True,
                         check=True)
    return {m for line in run.stdout.splitlines()
            if (m := line.removeprefix("cp results/").removesuffix(" docs/gallery/"))
            != line and line.endswith(" docs/gallery/")}


def test_make_figures_writes_the_gallery():
    """Every gallery PNG is copied there by `make figures`, `make continuation`, `make
    designs` or `make stiff-limit` at full resolution; QUICK=1 leaves the gallery alone."""
    made = gallery_copies("figures", "continuation", "designs", "stiff-limit")
    shown = {p.name for p in (ROOT / "docs" / "gallery").glob("*.png")}
    assert shown <= made, sorted(shown - made)
    assert not gallery_copies("figures", "stiff-limit", "QUICK=1")


def test_every_gallery_figure_names_the_command_that_makes_it():
    """Each row of the gallery page shows one PNG and a `make TARGET` that writes exactly
    that PNG into docs/gallery/ (so the page cannot point at a target that makes another
    figure, or at none)."""
    rows = [line for line in (ROOT / "docs" / "gallery.md").read_text().splitlines()
            if line.startswith("| [![")]
    shown = {p.name for p in (ROOT / "docs" / "gallery").glob("*.png")}
    named = set()
    for row in rows:
        png = re.search(r"\]\(gallery/([^)]+\.png)\)", row).group(1)
        targets = re.findall(r"`make ([a-z0-9-]+)`", row)
        assert len(targets) == 1, f"gallery row of {png} names {targets or 'no'} make target"
        assert gallery_copies(targets[0]) == {png}, f"`make {targets[0]}` does not make {png}"
        named.add(png)
    assert named == shown, sorted(shown ^ named)
