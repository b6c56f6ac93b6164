# Thin entry points; the work is in scripts/. Every target that needs the workspace runs setup first
# (idempotent: apt packages, venv, build are skipped when already up to date).
.PHONY: setup build demo test bench clean

setup:
	scripts/setup.sh

build: setup

demo: setup
	scripts/demo.sh

# Tests and benchmarks are built only for these targets (SIXDOF_BUILD_TESTS / SIXDOF_BUILD_BENCHMARKS).
test:
	SIXDOF_BUILD_TESTS=ON scripts/setup.sh
	scripts/test.sh

bench:
	SIXDOF_BUILD_BENCHMARKS=ON scripts/setup.sh
	scripts/bench.sh

clean:
	rm -rf build install log .setup-stamps
