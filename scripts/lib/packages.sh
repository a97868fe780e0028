# shellcheck shell=bash
# Sourced, not run: require_debian_packages PKG... installs the Debian packages that are missing,
# as root with apt-get, otherwise through sudo (which may ask for a password). It does nothing,
# not even `apt-get update`, when all of them are installed already, and on a system without
# dpkg/apt-get it only says what it could not check. Used by scripts/test, scripts/bench and the
# packages stage of .ci/run, so that the three install the same way.

require_debian_packages() {
  if ! command -v dpkg-query >/dev/null 2>&1 || ! command -v apt-get >/dev/null 2>&1; then
    echo "not a Debian system (no dpkg-query/apt-get): make sure these are installed: $*" >&2
    return 0
  fi
  local missing=() p
  for p in "$@"; do
    [[ $(dpkg-query -W -f='${Status}' "$p" 2>/dev/null) == "install ok installed" ]] ||
      missing+=("$p")
  done
  if ((${#missing[@]} == 0)); then
    return 0
  fi
  echo "installing the missing Debian packages: ${missing[*]}"
  local sudo=()
  if ((EUID != 0)); then
    if ! command -v sudo >/dev/null 2>&1; then
      echo "error: not root and no sudo; as root, run: apt-get install ${missing[*]}" >&2
      return 1
    fi
    sudo=(sudo)
    # Without a terminal sudo cannot ask for a password: fail with a clear message instead.
    if [[ ! -t 0 ]] && ! sudo -n true 2>/dev/null; then
      echo "error: sudo needs a password and there is no terminal; as root, run:" >&2
      echo "  apt-get install ${missing[*]}" >&2
      return 1
    fi
  fi
  local attempt
  for attempt in 1 2 3; do  # mirrors fail now and then; a retry usually gets through
    if "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get -q update </dev/null; then
      break
    fi
    if ((attempt == 3)); then
      echo "error: apt-get update failed 3 times" >&2
      return 1
    fi
    sleep 10
  done
  if ! "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get -q install -y \
    --no-install-recommends -o Dpkg::Use-Pty=0 "${missing[@]}" </dev/null; then
    echo "error: apt-get install ${missing[*]} failed" >&2
    return 1
  fi
}

# What a build of tumble needs (Boost for the explicit integrator's Boost.Odeint, oneTBB for the
# ensembles across cores, Open MPI and its mpirun for the ensembles across ranks), and what the
# benchmarks add (Google Benchmark; Boost.Odeint and SUNDIALS' ARKODE for tumble_bench's floors,
# listed again so the benchmarks keep them whatever the library's list becomes; SuiteSparse's KLU
# for the IDA study of A05, mechanisms/ida_ggl.hpp; matplotlib for tumble_bench's plots).
# shellcheck disable=SC2034  # used by the scripts that source this file
TUMBLE_BUILD_PACKAGES=(cmake make g++ libeigen3-dev libsundials-dev catch2 libboost-dev libtbb-dev
                       mpi-default-dev openmpi-bin)
# shellcheck disable=SC2034
TUMBLE_BENCH_PACKAGES=(libbenchmark-dev libboost-dev libsundials-dev libsuitesparse-dev python3
                       python3-matplotlib)
