# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""Browser pages of the viewer and joint_state_publisher_gui (viser) and the viewer's displays."""
