# Thin entry points; the work is in scripts/. Every target that needs the workspace runs setup first
# (idempotent: apt packages, venv, build are skipped when already up to date).
.PHONY: setup build demo demo-sort demo-pack test bench bench-build bench-pick bench-pack bench-sort fuzz soak clean

setup:
	scripts/setup.sh

build: setup

demo: setup
	scripts/demo.sh

# Vision-based sorting, headless: the camera-based planning scene and sort_objects.py (artifacts/sort_*).
demo-sort: setup
	scripts/demo_sort.sh

# Packing from a running belt without a screen: pack_objects.py fills a box 2x2 (artifacts/pack_*).
demo-pack: setup
	scripts/demo_pack.sh

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

# Packing from a running belt at 0.2 m/s (100 objects), 0.1 and 0.3 m/s (10 each), in real time: picks per minute,
# placed correctly, failures by class (the "pack" section of bench/results.md); ARGS go to bench/pack_bench.py.
bench-pack: setup
	scripts/bench_pack.sh $(ARGS)

# Soak, not part of `make test`: 500 pick-and-place cycles with every node's RSS sampled; fails on any failed
# cycle or a node growing by more than 5 MB (the "soak" section of bench/results.md); CONFIG as for bench-pick.
soak: setup
	scripts/bench_pick.sh --soak $(if $(CONFIG),--config $(CONFIG)) $(ARGS)

# Build cost of a fresh clone (cold, against the previous defaults); add ARGS=--apt for the Debian packages.
bench-build: setup
	scripts/bench_build.sh $(ARGS)

clean:
	rm -rf build install log .setup-stamps
