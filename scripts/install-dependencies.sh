#!/bin/sh
# Installs the Debian 12 packages the project needs, only those that are missing.
# Run as root or with sudo available. Idempotent: does nothing when all are present.
set -eu
packages="g++ cmake make ccache libcgal-dev libboost-graph-dev libboost-test-dev libeigen3-dev libspectra-dev libtbb-dev libcgal-demo libpng-dev doxygen pybind11-dev python3-dev python3-numpy python3-pytest python3-pip python3-venv python3-tqdm python3-distributed"
missing=""
for p in $packages; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing="$missing $p"
  fi
done
if [ -z "$missing" ]; then
  echo "install-dependencies: all packages present" >&2
  exit 0
fi
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
echo "install-dependencies: installing$missing" >&2
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
