# Shared by run.sh and test.sh: install what is missing, then configure and build in Release.
# Sourced, not executed.

# Debian 12 packages the project builds and runs with.
MG_PACKAGES=(
  build-essential cmake ccache clang-format
  libcgal-dev libopenmesh-dev libeigen3-dev libtbb-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libbenchmark-dev libopenvdb-dev clang libclang-rt-14-dev
  povray povray-includes meshlab xvfb xauth
  python3 python3-matplotlib python3-numpy python3-dev pybind11-dev python3-distributed
)

# Debian's interpreter: it sees the python3-* packages (a pyenv or venv python3 on PATH does not).
MG_PYTHON=/usr/bin/python3
MG_BUILD_DIR=${MG_BUILD_DIR:-build}

mg_install() {
  local missing=() p
  for p in "${MG_PACKAGES[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
      missing+=("$p")
    fi
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  local cmd="apt-get install -y --no-install-recommends ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then
    echo "Missing Debian packages. As root, run:" >&2
    echo "  apt-get update && $cmd" >&2
    exit 1
  fi
  echo "== installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  $cmd
}

# The sanitizer job's build: the unit tests (label `unit`) with AddressSanitizer and
# UndefinedBehaviorSanitizer, in $MG_SANITIZE_DIR.
MG_SANITIZE_DIR=${MG_SANITIZE_DIR:-build-sanitize}
mg_build_sanitize() {
  local extra=()
  [ "${CI:-}" = "true" ] && extra+=(-DMG_WERROR=ON)
  cmake -S . -B "$MG_SANITIZE_DIR" -DCMAKE_BUILD_TYPE=Release -DMG_SANITIZE=ON \
    -DPython3_EXECUTABLE="$MG_PYTHON" "${extra[@]}"
  cmake --build "$MG_SANITIZE_DIR" --parallel "$(nproc)" --target unit_tests
}

# The fuzz job's build: the readers' libFuzzer targets (clang), in $MG_FUZZ_DIR.
MG_FUZZ_DIR=${MG_FUZZ_DIR:-build-fuzz}
mg_build_fuzz() {
  local extra=()
  [ "${CI:-}" = "true" ] && extra+=(-DMG_WERROR=ON)
  cmake -S . -B "$MG_FUZZ_DIR" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++ \
    -DMG_FUZZ=ON -DPython3_EXECUTABLE="$MG_PYTHON" "${extra[@]}"
  cmake --build "$MG_FUZZ_DIR" --parallel "$(nproc)" \
    --target fuzz_ma fuzz_off fuzz_obj fuzz_ply fuzz_stl fuzz_view
}

mg_build() {
  local extra=()
  # CI builds with warnings as errors (STYLE.md).
  [ "${CI:-}" = "true" ] && extra+=(-DMG_WERROR=ON)
  cmake -S . -B "$MG_BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE="$MG_PYTHON" "${extra[@]}"
  cmake --build "$MG_BUILD_DIR" --parallel "$(nproc)"
}
