# Thin wrappers; the work is in scripts/. Each target installs what it needs first.
.PHONY: demo test bench build bootstrap clean

bootstrap:
	bash scripts/bootstrap

build: bootstrap
	bash scripts/build

demo: build
	bash scripts/demo

test: build
	bash scripts/run_tests

# The benchmarks also need their benchmark-only packages (IPOPT): bootstrap --bench.
bench: build
	bash scripts/bootstrap --bench
	bash scripts/bench

clean:
	rm -rf .build_ws build_ws
