# tetrafoil — the two commands a newcomer needs are `make demo` and `make test`.
# Everything they need is installed by the targets themselves.

CARGO ?= cargo
OUT ?= out

.PHONY: demo test lint setup samples bench clean plugins

## setup: install what the build needs: a project-local OpenCASCADE 7.8.1 in .occt/ (from PyPI
## wheels, seconds) unless DEP_OCCT_ROOT names another OCCT >= 7.8
setup:
	@command -v $(CARGO) >/dev/null || { echo "cargo not found: install Rust (https://rustup.rs)"; exit 1; }
	@if [ -z "$${DEP_OCCT_ROOT:-}" ]; then scripts/install-occt.sh; fi

## demo: mesh the shipped wing sample (swept NACA 0012 half-wing, wake sheet, far-field box)
## end to end: SU2 for the solver, VTU for ParaView, a JSON report, and the quality summary;
## then refined from its skin (stretched layers), then the same wing as CAD
## (samples/wing_step/wing_in_box.step, read through the OpenCASCADE plugin built beside the binary),
## then a hemisphere-cylinder flow domain read through the analytic C geometry plugin
demo: setup plugins
	mkdir -p $(OUT)
	./target/release/tetrafoil check samples/wing/case.toml
	./target/release/tetrafoil mesh samples/wing/case.toml -o $(OUT)/wing.su2 -o $(OUT)/wing.vtu --report $(OUT)/wing-report.json
	./target/release/tetrafoil quality $(OUT)/wing.vtu
	./target/release/tetrafoil mesh samples/wing/case.toml --refine-faces wing_upper,wing_lower,wing_tip --first 0.002 --growth 1.2 --constant 3 -o $(OUT)/wing_refined.su2 -o $(OUT)/wing_refined.vtu --report $(OUT)/wing_refined-report.json
	./target/release/tetrafoil check samples/wing_step/wing_in_box.step
	./target/release/tetrafoil mesh samples/wing_step/wing_in_box.step -o $(OUT)/wing_step.su2 -o $(OUT)/wing_step.vtu
	./target/release/tetrafoil plugins
	./target/release/tetrafoil mesh samples/hemisphere_cylinder/domain.analytic -o $(OUT)/hemisphere_cylinder.su2 -o $(OUT)/hemisphere_cylinder.vtu
	@echo "wrote $(OUT)/wing.su2 (SU2), $(OUT)/wing.vtu (open it in ParaView) and $(OUT)/wing-report.json"
	@echo "$(OUT)/wing_refined.su2 + .vtu: the wing with stretched layers on its skin"
	@echo "and $(OUT)/wing_step.su2 + .vtu from the STEP wing, read through the OpenCASCADE plugin"
	@echo "$(OUT)/hemisphere_cylinder.vtu: a flow domain read by the analytic C plugin (plugins/analytic-c)"

## test: every test of every crate, then formatting and lints (headless Chromium, for the
## service's web page test, meshio and Gmsh, for the writer tests, OpenFOAM, for the
## checkMesh test, and the CGNS library with cgnscheck, are installed first when missing). With TETRAFOIL_SLOW_TESTS=1 (CI sets it) the slow CAD-corpus tests run too, in
## the release profile, after the others.
test: setup
	scripts/install-chromium.sh
	scripts/install-readers.sh
	scripts/install-openfoam.sh
	scripts/install-cgns.sh
	env -u TETRAFOIL_SLOW_TESTS $(CARGO) test --workspace
	# OpenCASCADE built in (the `occt` feature) must keep meshing as the plugin does
	env -u TETRAFOIL_SLOW_TESTS $(CARGO) test --features occt --test plugin_occt
	@if [ -n "$${TETRAFOIL_SLOW_TESTS:-}" ]; then \
	  echo "slow CAD-corpus tests (release profile)"; \
	  $(CARGO) test --release --test volume_cad --test surface_cad --test refine_cad; \
	fi
	$(MAKE) lint

## plugins: the release binary and, beside it (where it finds them), the geometry plugins:
## OpenCASCADE's (libtetrafoil_occt.so, from geometry-bridge) and the analytic one written in
## C (plugins/analytic-c), built with the system C compiler
PLUGIN_SUFFIX := $(if $(filter Darwin,$(shell uname -s)),.dylib,.so)
plugins:
	$(CARGO) build --release
	$(CARGO) build --release -p tetrafoil-occt
	$${CC:-cc} -std=c99 -Wall -Wextra -O2 -fPIC -shared -Iinclude plugins/analytic-c/*.c \
	  -o target/release/libtetrafoil_analytic$(PLUGIN_SUFFIX).tmp -lm
	mv target/release/libtetrafoil_analytic$(PLUGIN_SUFFIX).tmp target/release/libtetrafoil_analytic$(PLUGIN_SUFFIX)

lint:
	$(CARGO) fmt --all -- --check
	$(CARGO) clippy --workspace --all-targets -- -D warnings
	# tetrafoil with OpenCASCADE built in (the `occt` feature) must keep building
	$(CARGO) clippy --features occt --all-targets -- -D warnings

## samples: regenerate samples/*/case.toml from the construction code (and the STEP wing,
## built with OpenCASCADE)
samples:
	$(CARGO) run --release --example write_samples

clean:
	$(CARGO) clean
	rm -rf $(OUT)
