# Shared by scripts/demo, scripts/test and scripts/bench: install what is missing, configure once,
# build incrementally. Source it; do not run it.

ANCF_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
ANCF_PACKAGES=(g++ cmake make pkg-config libeigen3-dev libfmt-dev libsundials-dev
               libsuitesparse-dev libgtest-dev libgmock-dev libbenchmark-dev
               libtomlplusplus-dev libcli11-dev python3-matplotlib
               libopenmpi-dev openmpi-bin
               python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest)

# Install only the Debian packages that are not installed yet (fast when nothing is missing).
ancf_ensure_packages() {
  local missing=()
  for p in "${ANCF_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if ((${#missing[@]})); then
    echo "ancf: installing ${missing[*]}" >&2
    local sudo=""
    [[ $(id -u) -ne 0 ]] && sudo=sudo
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  fi
}

# ancf_build DIR [cmake options...]: configure DIR if it has no cache yet, then build incrementally.
ancf_build() {
  local dir=$1
  shift
  if [[ ! -f "$dir/CMakeCache.txt" ]]; then
    cmake -S "$ANCF_ROOT" -B "$dir" "$@" >/dev/null
  fi
  cmake --build "$dir" -j"$(nproc)"
}
