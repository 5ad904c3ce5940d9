# Shared environment for the project's scripts (sourced, not run).
# System ROS lives in /usr; a pyenv python3 earlier on PATH lacks the ROS modules.
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:$PATH"
export ROS_HOSTNAME="${ROS_HOSTNAME:-localhost}"
MD_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export MD_ROOT
export MD_BUILD="${MD_BUILD:-$MD_ROOT/_build}"
export ROS_HOME="${ROS_HOME:-$MD_BUILD/ros_home}"
export ROS_LOG_DIR="${ROS_LOG_DIR:-$ROS_HOME/log}"
mkdir -p "$ROS_LOG_DIR"

md_build() {
  # Configure (once) and build everything, including tests, out of tree in $MD_BUILD.
  if [ ! -f "$MD_BUILD/CMakeCache.txt" ]; then
    cmake -S "$MD_ROOT" -B "$MD_BUILD" -DPYTHON_EXECUTABLE=/usr/bin/python3 \
      -DCMAKE_BUILD_TYPE=Release -DCATKIN_ENABLE_TESTING=ON -DMD_WERROR="${MD_WERROR:-${CI:+ON}}" \
      ${MD_CMAKE_ARGS:-} $(command -v ccache >/dev/null && echo -DCMAKE_CXX_COMPILER_LAUNCHER=ccache) >"$MD_BUILD/configure.log" 2>&1 \
      || { cat "$MD_BUILD/configure.log"; return 1; }
  fi
  cmake --build "$MD_BUILD" -j"$(nproc)" -- all tests
}
