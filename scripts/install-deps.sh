#!/usr/bin/env bash
# Installs what fluidbed needs to build, test and make its pictures, from Debian's packages.
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
PACKAGES=(
  g++ cmake ninja-build pkg-config
  dpkg-dev file         # the Debian package (cpack -G DEB): dpkg-shlibdeps reads its dependencies
  libtomlplusplus-dev   # scene files
  libcli11-dev          # command line
  nlohmann-json3-dev    # summary.json
  libeigen3-dev         # sparse solvers for the gas pressure correction
  libgtest-dev libgmock-dev libbenchmark-dev
  libstb-dev fonts-dejavu-core
  libosmesa6-dev        # offscreen GL (llvmpipe): frames and render tests without a display
  zlib1g-dev            # PNG frames
  libglfw3-dev          # windows (the viewer)
  libimgui-dev          # the viewer's panel (Dear ImGui; its GLFW and OpenGL 3 backends as sources)
  python3-glad          # generates the GL loader at build time
  ffmpeg                # DIR/video.mp4; ffprobe in the render tests
  xvfb xauth            # a virtual display: the window backend's test (xvfb-run)
  xdotool               # drives the viewer's window with a pointer and keys in its tests
  python3-vtk9          # reads the VTK files back in the render tests (ParaView's readers)
  liggghts              # the peer DEM code: `fluidbed export --to liggghts` decks are run in tests
  pybind11-dev python3-dev python3-numpy  # the Python module (import fluidbed)
  python3-pytest        # its tests
  python3-nbclient python3-nbformat python3-ipykernel python3-matplotlib  # the notebooks in assets/notebooks, run in a test
  openfoam              # DPMFoam: `fluidbed export --to openfoam` cases are run in tests (installs in ~10 s)
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
