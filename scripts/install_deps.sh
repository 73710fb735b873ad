#!/usr/bin/env bash
# Installs the Debian 12 packages the project builds, tests and runs with; does nothing when they
# are all present. Run as root (or with sudo).
set -euo pipefail

packages=(
  build-essential cmake pkg-config clang-format
  libeigen3-dev                    # Eigen 3.4
  libsuitesparse-dev libopenblas-dev  # CHOLMOD with an optimized BLAS
  liblcm-dev liblcm-bin            # LCM 1.3: library, lcm-gen, lcm-logger, lcm-logplayer
  liblcm-lua lua5.2                # controllers/lua: LCM's Lua module is built for Lua 5.2
  liblcm-java default-jdk-headless  # controllers/java, matlab: lcm.jar; javac --release 8, jar
  libhdf5-dev                      # HDF5 1.10, C and C++
  libyaml-cpp-dev                  # scene files
  libcgal-dev libassimp-dev        # obstacles: spatial index (AABB tree), OBJ and STL files
  libvigraimpex-dev                # reduced model: the non-negative LASSO path (header-only use)
  libgtest-dev                     # GoogleTest
  python3 python3-h5py python3-numpy  # reading run logs back in tests and scripts
  python3-matplotlib               # scripts/draw_midsagittal.py, scripts/plot_run.py
  pybind11-dev python3-dev python3-pytest  # python/: the simulator as a Python module, its tests
  python3-distributed python3-scipy  # python/tongue_sweep: sweeps on dask.distributed, fits with scipy.optimize
  libboost-dev nlohmann-json3-dev  # viewer: HTTP and WebSocket (Boost.Beast), JSON
  libjs-three                      # viewer/web: three.js, served by tongue_viewer itself
  chromium chromium-driver python3-selenium python3-pil  # the viewer's browser tests, scripts/render_run.py
  ffmpeg                           # scripts/render_run.py --mp4
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi
echo "install_deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
