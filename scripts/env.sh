# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
# Source me (bash): activates .venv, sources the colcon install, sets ROS defaults.
# (interim version; scripts/setup creates what this needs)
_amr_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$_amr_root/.venv/bin/activate"
export AMENT_PREFIX_PATH="$VIRTUAL_ENV${AMENT_PREFIX_PATH:+:$AMENT_PREFIX_PATH}"
[ -f "$_amr_root/install/setup.bash" ] && source "$_amr_root/install/setup.bash"
export ROS_AUTOMATIC_DISCOVERY_RANGE="${ROS_AUTOMATIC_DISCOVERY_RANGE:-LOCALHOST}"
export PATH="$_amr_root/install/amr_description/lib/amr_description:$PATH"
unset _amr_root
