# Thin entry points; the work is in scripts/. Every target that needs the workspace runs setup first
# (idempotent: apt packages, venv, build are skipped when already up to date).
.PHONY: setup build demo demo-sort test bench bench-build bench-pick bench-sort fuzz soak clean

setup:
	scripts/setup.sh

build: setup

demo: setup
	scripts/demo.sh

# Vision-based sorting, headless: the camera-based planning scene and sort_objects.py (artifacts/sort_*).
demo-sort: setup
	scripts/demo_sort.sh

# Seeded random sorting layouts: detection accuracy and sorting success (the "sort" section of bench/results.md).
bench-sort: setup
	scripts/bench_sort.sh $(ARGS)

# Tests and benchmarks are built only for these targets (SIXDOF_BUILD_TESTS / SIXDOF_BUILD_BENCHMARKS).
test:
	SIXDOF_BUILD_TESTS=ON scripts/setup.sh
	scripts/test.sh

bench:
	SIXDOF_BUILD_BENCHMARKS=ON scripts/setup.sh
	scripts/bench.sh

# Seeded fuzzing of every move_group and simulator service and action with more requests than `make test` sends.
fuzz:
	SIXDOF_BUILD_TESTS=ON scripts/setup.sh
	scripts/fuzz.sh

# Randomized pick and place on a headless stack: 100 seeded trials, failures classified (the "pick" section of
# bench/results.md); CONFIG=<package name or folder>: a generated config package's robot instead of the sixdof arm
# ("pick, <package>"); ARGS go to bench/pick_bench.py (e.g. ARGS="--trials 20 --seed 7").
bench-pick: setup
	scripts/bench_pick.sh $(if $(CONFIG),--config $(CONFIG)) $(ARGS)

# Soak, not part of `make test`: 500 pick-and-place cycles with every node's RSS sampled; fails on any failed
# cycle or a node growing by more than 5 MB (the "soak" section of bench/results.md); CONFIG as for bench-pick.
soak: setup
	scripts/bench_pick.sh --soak $(if $(CONFIG),--config $(CONFIG)) $(ARGS)

# Build cost of a fresh clone (cold, against the previous defaults); add ARGS=--apt for the Debian packages.
bench-build: setup
	scripts/bench_build.sh $(ARGS)

clean:
	rm -rf build install log .setup-stamps
