# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""ros2_control-style hardware interfaces, controllers and the controller manager."""
