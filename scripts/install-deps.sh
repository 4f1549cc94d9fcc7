#!/usr/bin/env bash
# Installs everything mixflow needs from Debian 12 packages, OpenFOAM's headers from Debian's own
# source package (Debian ships OpenFOAM's libraries but not its headers; see cfd/README.md), and
# this checkout's Python package python/mixflow with its `mixflow` command (python/README.md).
# Idempotent: a second run checks and returns in about a second.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)

PKGS=(build-essential cmake pkg-config git
      openfoam libopenfoam openfoam-examples
      liggghts libliggghts-dev
      libopenmpi-dev openmpi-bin
      libhdf5-dev hdf5-tools
      python3 python3-numpy python3-h5py python3-matplotlib
      python3-pip python3-setuptools python3-wheel python3-pyflakes
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
# The Python package: an editable install into Debian's python3 (the one with numpy and h5py), so
# that `import mixflow` finds this checkout's python/mixflow and `mixflow` is a command on PATH.
# Nothing is downloaded (--no-index, --no-deps, --no-build-isolation: setuptools and wheel are
# Debian's); Debian marks its python3 as externally managed (PEP 668), hence
# --break-system-packages (pip writes to /usr/local only). Reinstalled only when the installed
# package is another checkout's, of another version, or has no command.
PY=/usr/bin/python3
want="$ROOT/python/mixflow/__init__.py $(sed -n 's/^version = "\(.*\)"$/\1/p' "$ROOT/python/pyproject.toml")"
have=$(cd / && "$PY" -I -c 'import importlib.metadata as m, mixflow; print(mixflow.__file__, m.version("mixflow"))' 2>/dev/null || true)
if [ "$have" != "$want" ] || [ ! -x /usr/local/bin/mixflow ]; then
  echo "[install-deps] installing the Python package from $ROOT/python (editable)"
  $SUDO "$PY" -m pip install --quiet --no-index --disable-pip-version-check --root-user-action=ignore \
    --break-system-packages --no-build-isolation --no-deps --editable "$ROOT/python"
fi
echo "[install-deps] ok (OpenFOAM source at $FOAM_SRC; Python package mixflow from $ROOT/python)"
