# Thin entry points; the work is in scripts/. Every target that needs the workspace runs setup first
# (idempotent: apt packages, venv, build are skipped when already up to date).
.PHONY: setup build demo demo-sort test bench bench-build bench-sort fuzz clean

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

# Build cost of a fresh clone (cold, against the previous defaults); add ARGS=--apt for the Debian packages.
bench-build: setup
	scripts/bench_build.sh $(ARGS)

clean:
	rm -rf build install log .setup-stamps
