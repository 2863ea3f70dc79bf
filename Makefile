# softimpact: every target creates .venv and installs what it needs.
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
SI := $(VENV)/bin/softimpact
STAMP := $(VENV)/.installed-stamp
PYTEST_ARGS ?=
.DEFAULT_GOAL := help

.PHONY: help install test test-fast test-nojit demo trajectory lint clean bench bench-precision \
	catalogues fig04 fig10 fig13-catalogue docs docs-check

install: $(STAMP)

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test,dask,docs]'
	$(PY) -m softimpact_cli.analysis.warmup
	touch $(STAMP)

# The whole suite on both cores (pytest-xdist): 1587 tests in 9 min 28 s on 2 cores
# after the install (pip, then kernels compiled in 384 s): 16 min 33 s in all on a clean
# clone (2026-11-27, `.ci/run` with empty caches). The interrupt tests wait
# on events with generous deadlines, not on an idle machine; kernels a test compiles are
# saved under a lock (kernels/numba_cache.py), so the two workers may compile at once.
# --durations names the slowest tests in the log (where the suite's time goes).
test: $(STAMP)
	SOFTIMPACT_HYPOTHESIS=ci $(PY) -m pytest -n 2 --durations=30 $(PYTEST_ARGS)

# The suite without the tests marked slow, on both cores: about 6 minutes (1440 tests,
# 723 s of CPU, 2026-11-27; benchmarks/pytest_cpu_per_test.py measures it per test).
test-fast: $(STAMP)
	$(PY) -m pytest -m "not slow" -n 2 $(PYTEST_ARGS)

# Pure-Python run of the kernels (slow): for debugging and coverage.
test-nojit: $(STAMP)
	NUMBA_DISABLE_JIT=1 $(PY) -m pytest -x -k "not slow" $(PYTEST_ARGS)

# The main job on a default scene: a 100 x 100 coupled-Duffing basin (figure 6(d) setting).
demo: $(STAMP)
	$(SI) sweep configs/demo_basins.toml -o results/demo.h5 --overwrite
	$(SI) plot basins results/demo.h5 -o results/demo.png
	@echo "result: results/demo.h5   figure: results/demo.png   (softimpact info results/demo.h5)"

trajectory: $(STAMP)
	$(SI) sweep configs/trajectory_duffing.toml -o results/trajectory.h5 --overwrite
	$(SI) plot trajectory results/trajectory.h5 -o results/trajectory.png

# QUICK=1 runs every figure scene at low resolution (for CI; see softimpact sweep --help).
QUICK ?=
QUICKFLAG := $(if $(QUICK),--quick,)
# The gallery of the documentation site (docs/gallery.md shows docs/gallery/*.png): a
# figure target at full resolution copies its PNG there; QUICK=1 figures stay in results/.
GALLERY = $(if $(QUICK),,cp $(1) docs/gallery/)

# Attractor catalogues (figures 4, 9-10 and 13's single body): HDF5 + PNG under results/.
catalogues: fig04 fig10 fig13-catalogue

fig04: $(STAMP)
	$(SI) sweep configs/fig04_duffing_catalogue.toml -o results/fig04.h5 --overwrite $(QUICKFLAG)
	$(SI) plot catalogue results/fig04.h5 -o results/fig04.png
	$(call GALLERY,results/fig04.png)

fig10: $(STAMP)
	$(SI) sweep configs/fig10_bilinear_catalogue.toml -o results/fig10.h5 --overwrite $(QUICKFLAG)
	$(SI) plot catalogue results/fig10.h5 -o results/fig10.png
	$(call GALLERY,results/fig10.png)

fig13-catalogue: $(STAMP)
	$(SI) sweep configs/fig13_bilinear_catalogue.toml -o results/fig13_catalogue.h5 --overwrite $(QUICKFLAG)
	$(SI) plot catalogue results/fig13_catalogue.h5 -o results/fig13_catalogue.png
	$(call GALLERY,results/fig13_catalogue.png)

# Basin figures (the study's section 5).
BASIN_FIGS := fig03 fig06 fig09 fig12 fig13 fig14ab fig14cd
FIGURES := $(BASIN_FIGS)

fig03: configs/figures/fig03_duffing_single_basins.toml
fig06: configs/figures/fig06_duffing_basins.toml
fig09: configs/figures/fig09_bilinear_single_basins.toml
fig12: configs/figures/fig12_bilinear_basins.toml
fig13: configs/figures/fig13_bilinear_basins.toml
fig14ab: configs/figures/fig14ab_bilinear_impacting.toml
fig14cd: configs/figures/fig14cd_duffing_impacting.toml
fig14: fig14ab fig14cd

DCRIT_FIGS := fig05 fig11
FIGURES += $(DCRIT_FIGS)
fig05: configs/figures/fig05_duffing_dcrit.toml
fig11: configs/figures/fig11_bilinear_dcrit.toml

$(DCRIT_FIGS): $(STAMP)
	$(SI) sweep $(filter %.toml,$^) -o results/$@.h5 --overwrite $(QUICKFLAG)
	$(SI) plot dcrit results/$@.h5 -o results/$@.png
	$(call GALLERY,results/$@.png)

STABILITY_FIGS := fig15a fig15b fig14c-t0 fig14c-random-t0
FIGURES += $(STABILITY_FIGS)
fig15a: configs/figures/fig15a_bilinear_stability.toml
fig15b: configs/figures/fig15b_duffing_stability.toml
fig14c-t0: configs/figures/fig14c_t0_stability.toml
fig14c-random-t0: configs/figures/fig14c_random_t0_stability.toml
fig15: fig15a fig15b

$(STABILITY_FIGS): $(STAMP)
	$(SI) sweep $(filter %.toml,$^) -o results/$@.h5 --overwrite $(QUICKFLAG)
	$(SI) info results/$@.h5
	$(if $(filter fig14c-random-t0,$@),,$(SI) plot stability results/$@.h5 -o results/$@.png)
	$(if $(filter fig14c-random-t0,$@),,$(call GALLERY,results/$@.png))

fig07: fig07-bifurcation fig07-basins
fig07-bifurcation: $(STAMP)
	$(SI) sweep configs/figures/fig07_duffing_bifurcation.toml -o results/fig07.h5 --overwrite \
		$(QUICKFLAG)
	$(SI) plot bifurcation results/fig07.h5 -o results/fig07.png
	$(call GALLERY,results/fig07.png)
	$(SI) info results/fig07.h5
fig07-basins: $(STAMP)
	$(SI) sweep configs/figures/fig07_duffing_basins.toml -o results/fig07_basins.h5 \
		--overwrite $(QUICKFLAG)
	$(SI) plot basins results/fig07_basins.h5 -o results/fig07_basins.png
	$(call GALLERY,results/fig07_basins.png)
FIGURES += fig07

# Figures 7's basins and 14(c, d) started at t0 = T/2, the start phase under which the
# study's plane shares are reproduced (docs/howto/reproduce.md; the reproduction table's
# runs fig07_basins_t0half, fig14cd_t0half): the scene with t0 = "T/2" added to its
# [initial_conditions] (results/<name>.toml, then swept and drawn like the t0 = 0 figure).
T0HALF_FIGS := fig07-basins-t0half fig14cd-t0half
fig07-basins-t0half: configs/figures/fig07_duffing_basins.toml
fig14cd-t0half: configs/figures/fig14cd_duffing_impacting.toml
$(T0HALF_FIGS): $(STAMP)
	@mkdir -p results
	sed '/^\[initial_conditions\]/a t0 = "T/2"' $(filter %.toml,$^) > results/$(subst -,_,$@).toml
	$(SI) sweep results/$(subst -,_,$@).toml -o results/$(subst -,_,$@).h5 --overwrite $(QUICKFLAG)
	$(SI) plot basins results/$(subst -,_,$@).h5 -o results/$(subst -,_,$@).png
	$(call GALLERY,results/$(subst -,_,$@).png)
.PHONY: $(T0HALF_FIGS)
FIGURES += $(T0HALF_FIGS)

map-d-phi: $(STAMP)
	$(SI) sweep configs/figures/map_duffing_d_phi.toml -o results/map_d_phi.h5 --overwrite \
		$(QUICKFLAG)
	$(SI) plot map results/map_d_phi.h5 -o results/map_d_phi.png
	$(call GALLERY,results/map_d_phi.png)
FIGURES += map-d-phi

# Tipping probabilities of the study's control scenario: d 22 -> 6 at phi = 0 (docs/howto/analyses.md).
tipping: $(STAMP)
	$(SI) sweep configs/tipping_duffing_d22_to_6.toml -o results/tipping_duffing_d22_to_6.h5 \
		--overwrite $(QUICKFLAG)
	$(SI) plot tipping results/tipping_duffing_d22_to_6.h5 -o results/tipping_duffing_d22_to_6.png

# Minimal fatal shock of figure 6(d)'s dominant solution (docs/howto/analyses.md).
fatal-shock: $(STAMP)
	$(SI) sweep configs/fatal_shock_duffing_6d.toml -o results/fatal_shock_duffing_6d.h5 \
		--overwrite $(QUICKFLAG)
	$(SI) plot fatal_shock results/fatal_shock_duffing_6d.h5 -o results/fatal_shock_duffing_6d.png

$(BASIN_FIGS): $(STAMP)
	$(SI) sweep $(filter %.toml,$^) -o results/$@.h5 --overwrite $(QUICKFLAG)
	$(SI) plot basins results/$@.h5 -o results/$@.png
	$(call GALLERY,results/$@.png)


.PHONY: figures map-d-phi tipping fatal-shock fig07 fig07-bifurcation fig07-basins fig14 fig15 $(BASIN_FIGS) $(DCRIT_FIGS) $(STABILITY_FIGS)

# How fractal are the basins (issue 17; docs/validation/fractality.md): each plane of
# figures 3, 9 and a zoom of 9 (one body, FRACTAL_RES_ONE cells per side at most) and of
# the coupled figures 6, 12, 13, 14(a-b) (FRACTAL_RES per side) swept, then measured: basin
# entropy against the box size, uncertainty exponent with its fit interval, Wada test.
# Results in results/fractality/ (<fig>.h5 the basins, <fig>_measures.h5 + .png the
# measures); about 15 min on a busy 2-core machine at the defaults (figure 12 ~6 min).
# FRACTAL_RES_ONE=200: figure 9 alone ~25 min (its verification redoes it twice).
# QUICK=1: 24 x 24 planes, a smoke test only (the measures need 100+ cells per side).
FRACTAL_RES ?= 64
FRACTAL_RES_ONE ?= 100
FRACTALITY := fractality-fig03 fractality-fig09 fractality-fig09-zoom fractality-fig06 \
	fractality-fig12 fractality-fig13 fractality-fig14ab
fractality: $(FRACTALITY)
fractality-fig03: configs/figures/fig03_duffing_single_basins.toml
fractality-fig09: configs/figures/fig09_bilinear_single_basins.toml
fractality-fig09-zoom: configs/fractality/fig09_zoom_basins.toml
fractality-fig06: configs/figures/fig06_duffing_basins.toml
fractality-fig12: configs/figures/fig12_bilinear_basins.toml
fractality-fig13: configs/figures/fig13_bilinear_basins.toml
fractality-fig14ab: configs/figures/fig14ab_bilinear_impacting.toml
$(FRACTALITY): $(STAMP)
	$(SI) sweep $(filter %.toml,$^) -o results/fractality/$(@:fractality-%=%).h5 --overwrite -q \
		$(QUICKFLAG) $(if $(QUICK),,--resolution $(if $(filter fractality-fig03 \
		fractality-fig09 fractality-fig09-zoom,$@),$(FRACTAL_RES_ONE),$(FRACTAL_RES)))
	$(SI) measure results/fractality/$(@:fractality-%=%).h5 \
		-o results/fractality/$(@:fractality-%=%)_measures.h5 --overwrite
	$(SI) plot fractality results/fractality/$(@:fractality-%=%)_measures.h5 \
		-o results/fractality/$(@:fractality-%=%)_measures.png
.PHONY: fractality $(FRACTALITY)

# Lyapunov exponents (docs/howto/lyapunov.md): Ueda's chaotic oscillator (the smooth
# reference), the catalogue of figure 14(c) beside its Floquet exponents, and the spectrum
# along c_c from figure 14(c)'s impacting orbit. About a minute in all.
LYAPUNOV := lyapunov-ueda lyapunov-fig14c-catalogue lyapunov-fig14c-c-c
lyapunov: $(LYAPUNOV)
lyapunov-ueda: configs/lyapunov_ueda.toml
lyapunov-fig14c-catalogue: configs/lyapunov_fig14c_catalogue.toml
lyapunov-fig14c-c-c: configs/figures/lyapunov_fig14c_c_c.toml
$(LYAPUNOV): $(STAMP)
	$(SI) sweep $(filter %.toml,$^) -o results/$(subst -,_,$@).h5 --overwrite $(QUICKFLAG)
	$(SI) plot lyapunov results/$(subst -,_,$@).h5 -o results/$(subst -,_,$@).png
.PHONY: lyapunov $(LYAPUNOV)

# Continuation (docs/howto/continuation.md): the single Duffing body's
# hysteresis loop in F (two folds, the saddle dashed, brute-force sweeps up and down),
# figure 7 as branches in d (grazing at the critical distances, impacting orbits, folds),
# Ueda's period-doubling cascade in F, figure 14(c)'s impacting orbit in c_c (its
# subcritical Neimark-Sacker point), and the pair's symmetric orbit at phi = pi in w (two
# branch points, the asymmetric pair switched onto), and a two-body chain with a kink, a
# stop and a wall in a body's phase (an S-shaped impacting branch: grazing, two folds).
# Measured for the gallery (docs/gallery.md, 2026-11-27, 2 cores at load 8-11, nice 19):
# 17 s, 72 s, 87 s, 40 s, 88 s, 55 s.
CONTINUATION := continuation-duffing-fold continuation-fig07 continuation-ueda \
	continuation-fig14c-ns continuation-pitchfork continuation-chain
continuation: $(CONTINUATION)
continuation-duffing-fold: configs/continuation/duffing_fold_F.toml
continuation-fig07: configs/continuation/fig07_duffing_continuation.toml
continuation-ueda: configs/continuation/ueda_period_doubling_F.toml
continuation-fig14c-ns: configs/continuation/fig14c_neimark_sacker_c_c.toml
continuation-pitchfork: configs/continuation/pitchfork_w.toml
continuation-chain: configs/continuation/chain_hysteresis_phi2.toml
$(CONTINUATION): $(STAMP)
	$(SI) sweep $(filter %.toml,$^) -o results/$(subst -,_,$@).h5 --overwrite $(QUICKFLAG)
	$(SI) plot continuation results/$(subst -,_,$@).h5 -o results/$(subst -,_,$@).png
	$(call GALLERY,results/$(subst -,_,$@).png)
	$(SI) info results/$(subst -,_,$@).h5
.PHONY: continuation $(CONTINUATION)

# Attractors that are not periodic (docs/howto/nonperiodic.md): figure 15(b)'s unresolved share at c_c = 3, 4
# and the period-5 bilinear design's point, split by the second stage into chaotic and
# quasi-periodic attractors (with their Lyapunov exponents), long-period orbits and long
# transients; and the basins of the first two on figure 14(c)'s plane. About 1, 4 and 10-16
# minutes on 2 cores shared with other jobs (the last without its verification).
CHAOS := chaos-fig15b chaos-design-p5
chaos: $(CHAOS) chaos-fig14c-basins
chaos-fig15b: configs/figures/chaos_fig15b_c_c.toml
chaos-design-p5: configs/figures/chaos_design_p5.toml
$(CHAOS): $(STAMP)
	$(SI) sweep $(filter %.toml,$^) -o results/$(subst -,_,$@).h5 --overwrite $(QUICKFLAG)
	$(SI) info results/$(subst -,_,$@).h5
	$(SI) plot stability results/$(subst -,_,$@).h5 --attractors -o results/$(subst -,_,$@).png
	$(call GALLERY,results/$(subst -,_,$@).png)
chaos-fig14c-basins: $(STAMP)
	$(SI) sweep configs/figures/chaos_fig14c_basins.toml -o results/chaos_fig14c_basins.h5 \
		--overwrite $(QUICKFLAG)
	$(SI) plot basins results/chaos_fig14c_basins.h5 -o results/chaos_fig14c_basins.png
	$(call GALLERY,results/chaos_fig14c_basins.png)
.PHONY: chaos chaos-fig14c-basins $(CHAOS)
FIGURES += $(CHAOS) chaos-fig14c-basins

# Designing for one solution (docs/howto/nonperiodic.md): choose (d, phi, k_c, c_c) so that only the target
# survives, verified by basin stability; a few minutes each on 2 cores.
DESIGNS := design-duffing design-bilinear
designs: $(DESIGNS)
design-duffing: configs/design_duffing.toml
design-bilinear: configs/design_bilinear.toml
$(DESIGNS): $(STAMP)
	$(SI) design $(filter %.toml,$^) -o results/$(subst -,_,$@).h5 --overwrite $(QUICKFLAG)
	$(SI) plot design results/$(subst -,_,$@).h5 -o results/$(subst -,_,$@).png
	$(call GALLERY,results/$(subst -,_,$@).png)
.PHONY: designs $(DESIGNS)

# Speed, side by side in one run (figure 6(d) basin): softimpact vs the study's method vs
# a scipy loop; plus basin-stability wall time and a profile. RES=500 BENCH_ARGS="--ref-sample 1000"
# for the 500 x 500 target.
RES ?= 100
bench: $(STAMP)
	$(PY) benchmarks/bench_basin.py --resolution $(RES) $(BENCH_ARGS)
	$(PY) benchmarks/bench_targets.py $(TARGET_ARGS)

# The defaults' targets (issue 15) in one run: figure 6(d) at 500 x 500 and the fractal
# planes 9, 12(a), 13(a), 14(a) at 100 x 100 against a tight reference, beside the settings
# before, the study's method and scipy; basin stability, a small sweep, its fixed cost,
# the integrator's overhead (results/bench/targets.md; about 30 min on 2 cores, references
# cached). TARGET_ARGS="--cold" also times a cold compile. Then the chain family's targets
# (issue 32: presets vs their chain form, a 6-body chain, a never-seen model's first run,
# a 3-body chain's stability and basin plane, the install's compile CPU of the presets and
# of the family apart; results/bench/chain_targets.md; CHAIN_TARGET_ARGS="--only six,fresh").
# Then issue 33's: a rigid-impact basin plane against the stiff soft stop (k_c = 1e6, same
# restitution, on its exact flow and on "auto"), CPU ratio in one run (results/bench/
# rigid_targets.md; the issue's 200 x 200 plane: 91 s CPU in all; RIGID_TARGET_ARGS=
# "--size 60" for a smaller one).
# bench-settings: the measurement behind the defaults (candidate settings on the same planes).
bench-targets: $(STAMP)
	$(PY) benchmarks/bench_targets.py $(TARGET_ARGS)
	$(PY) benchmarks/bench_chain_targets.py $(CHAIN_TARGET_ARGS)
	$(PY) benchmarks/bench_rigid_targets.py $(RIGID_TARGET_ARGS)

# The stiff limit (issue 33): a soft wall's stroboscopic orbit against the rigid wall's as
# k_c grows 1e2 .. 1e6, slope -1/2 (results/stiff_limit.png, copied to docs/gallery/ for the
# README and the gallery; about 15 s).
stiff-limit: $(STAMP)
	$(PY) benchmarks/stiff_limit.py --out results/stiff_limit.png
	$(call GALLERY,results/stiff_limit.png)
.PHONY: stiff-limit

bench-settings: $(STAMP)
	$(PY) benchmarks/bench_settings.py $(SETTINGS_ARGS)
.PHONY: bench-targets bench-settings

# Work-precision: error vs wall time of every integrator setting on a smooth trajectory,
# trajectories through contacts and the figure 6(d) basin (results/bench/precision.md,
# .png; ~15 min on 2 cores, the basin reference cached). QUICK=1 for a smoke run.
bench-precision: $(STAMP)
	$(PY) benchmarks/bench_precision.py $(QUICKFLAG)

# Extreme parameters (stiff stops, long transients, Duffing and bilinear extremes, both
# contact laws): the steps `auto` took with each method, statuses over a small plane,
# agreement with a tight reference; then auto's cost over dopri5 on the non-stiff figure
# scenes. Table: results/bench/extreme.md (a few minutes on 2 cores).
EXTREME_SIDE ?= 8
bench-extreme: $(STAMP)
	$(PY) benchmarks/bench_extreme.py --side $(EXTREME_SIDE)
	$(PY) benchmarks/bench_auto_overhead.py --append results/bench/extreme.md
.PHONY: bench-extreme

# Kernel speed of this checkout against revision BASE (default: the last commit, i.e. the
# uncommitted changes), as ratios, with every trajectory's counters compared: run it
# before and after a refactor (benchmarks/bench_refactor.py; ~5 min on 2 cores).
BASE ?= HEAD
bench-compare: $(STAMP)
	@base=$$(mktemp -d) && git archive $(BASE) | tar -x -C $$base && \
	$(PY) benchmarks/bench_refactor.py --base $$base $(BENCH_ARGS); \
	status=$$?; rm -rf $$base; exit $$status
.PHONY: bench-compare

# The documentation site (docs/, mkdocs.yml) into site/, offline and strict: a broken link,
# anchor or API reference fails the build. The tutorials run while it builds (each a few
# seconds), the scene-key and command references are generated from the code. Read it
# with a browser at site/index.html. tests/docs/test_site.py runs the same build.
docs: $(STAMP)
	NO_MKDOCS_2_WARNING=1 $(VENV)/bin/mkdocs build --strict --quiet

# The built site in headless Chromium (Debian's package, installed here when missing; the
# playwright package drives it, no browser download): every page loaded from a server on
# 127.0.0.1, failing on a console error, a failed request or an image that does not load;
# screenshots of three pages in results/docs-screenshots/ (docs/check_site.py).
CHROMIUM ?= /usr/bin/chromium
docs-check: docs
	@test -x $(CHROMIUM) || (apt-get update -qq && DEBIAN_FRONTEND=noninteractive \
		apt-get install -y -qq chromium)
	@$(PY) -c "import playwright" 2>/dev/null || $(PY) -m pip install --quiet -e '.[docs-check]'
	$(PY) docs/check_site.py site --screenshots results/docs-screenshots --chromium $(CHROMIUM)

lint: $(STAMP)
	$(VENV)/bin/ruff check .

clean:
	rm -rf $(VENV) *.egg-info .pytest_cache
	find . -name __pycache__ -type d -prune -exec rm -rf {} +

# The study, statement by statement: every run its 89 statements need (cached in
# results/reproduce/ by scene hash: a finished run is reused, a killed one resumes) and
# the table results/reproduce.md. QUICK=1: reduced sizes, under 10 minutes on 2 cores.
# REPRODUCE_ARGS="--only S9-S11" checks a subset.
REPRODUCE_ARGS ?=
reproduce: $(STAMP)
	nice -n 5 $(SI) reproduce --workers 2 $(QUICKFLAG) $(REPRODUCE_ARGS) \
		-o results/reproduce$(if $(QUICK),_quick,).md
.PHONY: reproduce

# every figure of the study (defined last: FIGURES is complete only here)
figures: catalogues $(FIGURES)

# `make` alone (or `make help`) lists the targets (.DEFAULT_GOAL above).
help:
	@echo "softimpact make targets (each creates .venv and installs on first use):"
	@echo "  demo              install, run configs/demo_basins.toml, plot results/demo.png"
	@echo "  install           create .venv and install softimpact (with test and dask extras)"
	@echo "  test              the whole test suite (PYTEST_ARGS=... passes options to pytest)"
	@echo "  test-fast         the suite without the tests marked slow"
	@echo "  test-nojit        the suite without numba compilation (slow; for debugging)"
	@echo "  lint              ruff"
	@echo "  docs              the documentation site -> site/ (strict; runs the tutorials)"
	@echo "  docs-check        docs, then every page in headless Chromium (screenshots)"
	@echo "  trajectory        configs/trajectory_duffing.toml -> results/trajectory.{h5,png}"
	@echo "  figures           every figure of the study (QUICK=1: low resolution, for CI)"
	@echo "  catalogues fig03 fig04 fig05 fig06 fig07 fig09 fig10 fig11 fig12 fig13"
	@echo "  fig13-catalogue fig14 fig14ab fig14cd fig14c-t0 fig14c-random-t0 fig15 fig15a"
	@echo "  fig15b map-d-phi  one figure each (results/<target>.{h5,png}; QUICK=1 works too)"
	@echo "  fig07-basins-t0half fig14cd-t0half   figures 7's basins and 14(c, d) at t0 = T/2"
	@echo "  designs design-duffing design-bilinear   designing for one solution"
	@echo "  lyapunov          Lyapunov exponents: Ueda, fig. 14(c) catalogue, along c_c"
	@echo "  continuation      branches of periodic orbits: Duffing folds in F, fig. 7 in d, Ueda, fig. 14(c) NS, pitchforks"
	@echo "  stiff-limit       a soft wall tending to the rigid one as k_c grows -> results/stiff_limit.png"
	@echo "  chaos             chaotic and quasi-periodic attractors: fig. 15(b) at c_c = 3, 4; the period-5 design"
	@echo "  reproduce         the study's 89 statements checked -> results/reproduce.md (QUICK=1)"
	@echo "  bench bench-precision bench-extreme       benchmarks (results/bench/)"
	@echo "  clean             remove .venv and caches"
