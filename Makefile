# Thin entry points; the work is in scripts/. Every target that needs the workspace runs setup first
# (idempotent: apt packages, venv, build are skipped when already up to date).
.PHONY: setup build demo test bench clean

setup:
	scripts/setup.sh

build: setup

demo: setup
	scripts/demo.sh

test: setup
	scripts/test.sh

bench: setup
	scripts/bench.sh

clean:
	rm -rf build install log .setup-stamps
