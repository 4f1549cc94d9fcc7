#!/usr/bin/env bash
# Installs everything mixflow needs from Debian 12 packages, and OpenFOAM's headers from Debian's own
# source package (Debian ships OpenFOAM's libraries but not its headers; see cfd/README.md).
# Idempotent: a second run checks and returns in about a second.
set -euo pipefail

PKGS=(build-essential cmake pkg-config git
      openfoam libopenfoam openfoam-examples
      liggghts libliggghts-dev
      libopenmpi-dev openmpi-bin
      libhdf5-dev hdf5-tools
      python3 python3-numpy python3-h5py python3-matplotlib
      libgtest-dev bzip2 dpkg-dev)

SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"

missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

SRC_LIST=/etc/apt/sources.list.d/mixflow-deb-src.sources
need_update=0
if [ ${#missing[@]} -gt 0 ]; then need_update=1; fi
if [ ! -f "$SRC_LIST" ] && ! grep -rqs '^[^#]*deb-src' /etc/apt/sources.list /etc/apt/sources.list.d/; then
  # OpenFOAM's source package gives the headers; only bookworm main's deb-src is needed. Reuse the
  # keyring the system's own Debian entry names, as apt refuses two Signed-By values for one source.
  keyring=$(grep -hs '^Signed-By:' /etc/apt/sources.list.d/debian.sources | head -n1 | awk '{print $2}')
  {
    echo "Types: deb-src"
    echo "URIs: http://deb.debian.org/debian"
    echo "Suites: bookworm"
    echo "Components: main"
    [ -n "$keyring" ] && echo "Signed-By: $keyring"
  } | $SUDO tee "$SRC_LIST" >/dev/null
  need_update=1
fi
if [ $need_update -eq 1 ]; then
  $SUDO apt-get update -qq
fi
if [ ${#missing[@]} -gt 0 ]; then
  echo "[install-deps] installing: ${missing[*]}"
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# OpenFOAM headers: extracted once into $MIXFLOW_DEPS (default /opt/mixflow-deps), lnInclude farms made
# with the source tree's own wmakeLnInclude.
DEPS=${MIXFLOW_DEPS:-/opt/mixflow-deps}
FOAM_SRC="$DEPS/openfoam-src"
STAMP="$FOAM_SRC/.mixflow-lninclude-done"
if [ ! -f "$STAMP" ]; then
  $SUDO mkdir -p "$DEPS"
  tmp=$(mktemp -d)
  (cd "$tmp" && apt-get source --download-only -qq openfoam >/dev/null)
  tarball=$(ls "$tmp"/openfoam_*.orig.tar.* | head -n1)
  $SUDO rm -rf "$FOAM_SRC" && $SUDO mkdir -p "$FOAM_SRC"
  $SUDO tar -xf "$tarball" -C "$FOAM_SRC" --strip-components=1
  rm -rf "$tmp"
  export WM_ARCH=linux64 WM_PROJECT_DIR="$FOAM_SRC"
  for lib in OpenFOAM OSspecific/POSIX finiteVolume meshTools fvOptions sampling dynamicMesh \
             dynamicFvMesh surfMesh fileFormats conversion \
             transportModels/incompressible transportModels/twoPhaseMixture \
             transportModels/interfaceProperties transportModels/immiscibleIncompressibleTwoPhaseMixture \
             TurbulenceModels/turbulenceModels TurbulenceModels/incompressible \
             Pstream/mpi; do
    [ -d "$FOAM_SRC/src/$lib" ] && (cd "$FOAM_SRC" && ${SUDO:+$SUDO -E} ./wmake/wmakeLnInclude -s "src/$lib" >/dev/null)
  done
  $SUDO touch "$STAMP"
fi
echo "[install-deps] ok (OpenFOAM source at $FOAM_SRC)"
