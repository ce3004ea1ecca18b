#!/usr/bin/env bash
# Installs what is missing, builds in Release into build/, then runs the whole test suite; in CI
# (CI=true) or with MG_SANITIZE=1, then the unit tests again, built with AddressSanitizer and
# UndefinedBehaviorSanitizer (build-sanitize/), and the readers' fuzz targets for a bounded
# number of inputs each (clang, build-fuzz/).
set -euo pipefail
cd "$(dirname "$0")"
source scripts/common.sh
mg_install
mg_build
ctest --test-dir "$MG_BUILD_DIR" --output-on-failure --parallel "$(nproc)" "$@"
if [ "${CI:-}" = "true" ] || [ "${MG_SANITIZE:-}" = "1" ]; then
  mg_build_sanitize
  ctest --test-dir "$MG_SANITIZE_DIR" --output-on-failure --parallel "$(nproc)" -L unit "$@"
  mg_build_fuzz
  ctest --test-dir "$MG_FUZZ_DIR" --output-on-failure --parallel "$(nproc)" -L fuzz "$@"
fi
