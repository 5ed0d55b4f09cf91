#!/usr/bin/env bash
# Installs what is missing, builds, and runs `tallow` with the given arguments. With none: the
# default preset in a window when a display exists, otherwise a headless capture into out/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/install-deps.sh"
# Only the program: the tests are built by scripts/test.sh (issue 40: the first picture sooner).
build="$(TALLOW_BUILD_TARGETS=tallow bash "$root/scripts/build.sh" | tail -n 1)"
cd "$root"
exec "$build/tallow" "$@"
