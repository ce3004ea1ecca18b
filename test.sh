#!/usr/bin/env bash
# Installs what is missing, builds in Release into build/, then runs the whole test suite.
set -euo pipefail
cd "$(dirname "$0")"
source scripts/common.sh
mg_install
mg_build
ctest --test-dir "$MG_BUILD_DIR" --output-on-failure --parallel "$(nproc)" "$@"
