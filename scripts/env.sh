# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
#
# Source me (bash or zsh), from any directory:  source scripts/env.sh
# Activates .venv, sources the colcon install, adds the venv prefix to AMENT_PREFIX_PATH, sets
# ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST unless already set, ROS_DISTRO=jazzy, ROS_VERSION=2
# and ROS_PYTHON_VERSION=3 unless set (as a ROS install's setup script does), and provides
# `ros2` (our CLI subset) only when no upstream ros2cli is installed. Run ./scripts/setup first.

if [ -n "${BASH_SOURCE:-}" ]; then
  _amr_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
elif [ -n "${ZSH_VERSION:-}" ]; then
  # shellcheck disable=SC2296
  _amr_root="$(cd "$(dirname "${(%):-%x}")/.." && pwd)"
else
  _amr_root="$(pwd)"
fi

if [ ! -x "$_amr_root/.venv/bin/python" ] || [ ! -f "$_amr_root/install/setup.bash" ]; then
  echo "amr_description: not set up yet; run $_amr_root/scripts/setup first" >&2
else
  # Upstream ros2cli present before we touch PATH (a real ROS 2 install)?
  _amr_upstream_ros2=''
  if command -v ros2 >/dev/null 2>&1; then
    case "$(command -v ros2)" in
      "$_amr_root"/*) ;;
      *) _amr_upstream_ros2=1 ;;
    esac
  fi

  # shellcheck disable=SC1091
  . "$_amr_root/.venv/bin/activate"
  case ":${AMENT_PREFIX_PATH:-}:" in
    *":$VIRTUAL_ENV:"*) ;;
    *) export AMENT_PREFIX_PATH="$VIRTUAL_ENV${AMENT_PREFIX_PATH:+:$AMENT_PREFIX_PATH}" ;;
  esac
  case ":${CMAKE_PREFIX_PATH:-}:" in
    *":$VIRTUAL_ENV:"*) ;;
    *) export CMAKE_PREFIX_PATH="$VIRTUAL_ENV${CMAKE_PREFIX_PATH:+:$CMAKE_PREFIX_PATH}" ;;
  esac
  # The colcon-generated scripts read unset variables: relax `set -u` while sourcing them.
  case "$-" in *u*) _amr_nounset=1; set +u ;; *) _amr_nounset='' ;; esac
  if [ -n "${ZSH_VERSION:-}" ]; then
    . "$_amr_root/install/setup.zsh"
  else
    . "$_amr_root/install/setup.bash"
  fi
  [ -n "$_amr_nounset" ] && set -u
  export ROS_AUTOMATIC_DISCOVERY_RANGE="${ROS_AUTOMATIC_DISCOVERY_RANGE:-LOCALHOST}"
  export ROS_DISTRO="${ROS_DISTRO:-jazzy}"
  export ROS_VERSION="${ROS_VERSION:-2}"
  export ROS_PYTHON_VERSION="${ROS_PYTHON_VERSION:-3}"

  # `ros2` from amr_description only when no upstream ros2cli exists: a directory holding just
  # a `ros2` link to our entry point (not all of lib/amr_description) goes on PATH.
  if [ -z "$_amr_upstream_ros2" ] &&
      [ -x "$_amr_root/install/amr_description/lib/amr_description/ros2" ]; then
    _amr_shim="$_amr_root/install/.amr_ros2_shim"
    if [ ! -e "$_amr_shim/ros2" ]; then
      mkdir -p "$_amr_shim"
      ln -sf ../amr_description/lib/amr_description/ros2 "$_amr_shim/ros2"
    fi
    case ":$PATH:" in
      *":$_amr_shim:"*) ;;
      *) export PATH="$_amr_shim:$PATH" ;;
    esac
  fi
  unset _amr_upstream_ros2 _amr_shim _amr_nounset
fi
unset _amr_root
