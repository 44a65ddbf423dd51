#!/bin/sh
# Installs the Debian 12 packages this project needs. Idempotent: does nothing when all are present.
# Usage: ./setup.sh            (as root, or with sudo available)
#        ./setup.sh --check    (only report what is missing; exit 1 if anything is)
#        ./setup.sh [--check] PACKAGE...   (the same for these packages instead of the project's;
#                               messages/lcm-spy.sh uses it for the Java ones)
set -eu

CHECK=""
if [ "${1:-}" = "--check" ]; then
  CHECK=1
  shift
fi

PACKAGES="
  g++ make cmake pkg-config
  clang-14 libclang-rt-14-dev libomp-14-dev
  libeigen3-dev libpng-dev
  libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev libstb-dev
  libyaml-cpp-dev nlohmann-json3-dev
  liblcm-dev liblcm-bin libglib2.0-dev
  libbullet-dev
  libassimp-dev libgmsh-dev
  libarpack2-dev libsuitesparse-dev libsndfile1-dev librtaudio-dev libasound2-dev
  googletest libgtest-dev libbenchmark-dev
  libboost-math-dev
  rt-tests stress-ng
  libegl-dev libgl-dev libegl1 libegl-mesa0 libgl1-mesa-dri libglfw3-dev xvfb
"
if [ $# -gt 0 ]; then
  PACKAGES="$*"
fi

missing=""
for p in $PACKAGES; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  case "$status" in
    *"install ok installed"*) ;;
    *) missing="$missing $p" ;;
  esac
done

if [ -z "$missing" ]; then
  exit 0
fi

echo "setup.sh: missing Debian packages:$missing"
if [ -n "$CHECK" ]; then
  exit 1
fi

if [ "$(id -u)" -eq 0 ]; then
  SUDO=""
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
  SUDO="sudo"
else
  echo "setup.sh: not running as root. Install them with:" >&2
  echo "  sudo apt-get update && sudo apt-get install -y --no-install-recommends$missing" >&2
  echo "or run: sudo ./setup.sh" >&2
  exit 1
fi

export DEBIAN_FRONTEND=noninteractive
# Fresh machines often have empty package lists; refresh only when something must be installed.
$SUDO apt-get update -q
# shellcheck disable=SC2086
$SUDO apt-get install -y -q --no-install-recommends $missing
echo "setup.sh: installed:$missing"
