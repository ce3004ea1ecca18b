#!/usr/bin/env bash
# Installs what is missing, builds in Release into build/, then runs the main job.
set -euo pipefail
cd "$(dirname "$0")"
source scripts/common.sh
mg_install
mg_build
"$MG_PYTHON" experiments/models.py --build "$MG_BUILD_DIR" --write-results --quiet
"$MG_PYTHON" experiments/reproduce.py --build "$MG_BUILD_DIR" "$@"
"$MG_PYTHON" experiments/medial_meshes.py --build "$MG_BUILD_DIR" "$@"
"$MG_PYTHON" experiments/simplify.py --build "$MG_BUILD_DIR" "$@"
