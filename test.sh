#!/usr/bin/env bash
# Installs what is missing, builds in Release into build/, then runs the whole test suite; in CI
# (CI=true) or with MG_SANITIZE=1, then the unit tests again, built with AddressSanitizer and
# UndefinedBehaviorSanitizer (build-sanitize/).
set -euo pipefail
cd "$(dirname "$0")"
source scripts/common.sh
mg_install
mg_build
ctest --test-dir "$MG_BUILD_DIR" --output-on-failure --parallel "$(nproc)" "$@"
if [ "${CI:-}" = "true" ] || [ "${MG_SANITIZE:-}" = "1" ]; then
  mg_build_sanitize
  ctest --test-dir "$MG_SANITIZE_DIR" --output-on-failure --parallel "$(nproc)" -L unit "$@"
fi
