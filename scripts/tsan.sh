#!/usr/bin/env bash
# ThreadSanitizer run of the multi-threaded CPU code: builds the no-GL test suite alone with
# -fsanitize=thread into build-tsan/ and runs the tests of the TBB reference integrator and the
# planar Monte Carlo (both tbb::parallel_for over shared images and tallies). A data race fails
# the run (TSAN_OPTIONS halt_on_error, tests/CMakeLists.txt); tests/tsan.supp lists what is
# suppressed in the uninstrumented TBB and Embree libraries, and why. Not part of CI: the build
# takes about as long as the Release one.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(TALLOW_SANITIZE=thread TALLOW_BUILD_TARGETS="tallow_tests" bash "$root/scripts/build.sh" | tail -n 1)"
ctest --test-dir "$build" --output-on-failure -R "${TALLOW_TSAN_TESTS:-^(ReferenceIntegrator|PlanarMc)\.}" --timeout 1800
