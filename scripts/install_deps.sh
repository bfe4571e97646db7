#!/usr/bin/env bash
# Installs the Debian packages dynslam needs, only those missing. Needs root (or sudo).
set -euo pipefail
PKGS=(build-essential cmake libmrpt-dev mrpt-apps libeigen3-dev libopencv-dev libgtest-dev libbenchmark-dev ccache)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all packages present"
  exit 0
fi
echo "install_deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
$SUDO apt-get update
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
