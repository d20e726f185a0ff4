#!/usr/bin/env bash
# Installs the Debian 12 packages the build and the tests need, when missing.
# As root: runs apt-get. As another user with packages missing: prints the
# exact apt command to run and exits 1. Nothing is vendored or downloaded at
# build time; Python's cantools (the independent CAN log decoder used by one
# HIL test) is not packaged by Debian 12 and is installed from PyPI into a
# venv under the build directory by the HIL tests' own set-up.
set -euo pipefail
# `bootstrap.sh` (make build / make demo): what the build and the demo use; the
# build configures the test executables too, hence the test frameworks.
PKGS=(
  build-essential cmake pkg-config git
  libeigen3-dev libceres-dev libopenblas-dev nlohmann-json3-dev zlib1g-dev libboost-dev
  libcmocka-dev libgtest-dev
  python3 python3-dev pybind11-dev
)
# `bootstrap.sh check` (make check): additionally what only the tests and gates use.
PKGS_CHECK=(
  valgrind
  clang libclang-rt-14-dev
  can-utils iproute2
  gcc-arm-none-eabi libnewlib-arm-none-eabi binutils-arm-none-eabi
  libxml2-utils
  qemu-system-x86 linux-image-amd64 busybox-static cpio kmod
  python3-numpy python3-scipy python3-venv
)
case "${1:-}" in
  "") ;;
  check) PKGS+=("${PKGS_CHECK[@]}") ;;
  *) echo "usage: bootstrap.sh [check]" >&2; exit 2 ;;
esac
# FRAC_BOOTSTRAP_EXTRA: extra package names, used by the bootstrap's own test.
# shellcheck disable=SC2206
PKGS+=(${FRAC_BOOTSTRAP_EXTRA:-})
missing=()
for p in "${PKGS[@]}"; do
  st=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [ "$st" = "install ok installed" ] || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "bootstrap: all ${#PKGS[@]} Debian packages present"
  exit 0
fi
cmd="apt-get update && apt-get install -y --no-install-recommends ${missing[*]}"
if [ "$(id -u)" -ne 0 ]; then
  echo "bootstrap: missing Debian packages: ${missing[*]}" >&2
  echo "bootstrap: run as root, then retry:" >&2
  echo "  sudo sh -c '$cmd'" >&2
  exit 1
fi
echo "bootstrap: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
