# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The viewer's displays, one module each, as RViz's display plugins.

A display (:class:`~amr_description.web.displays.base.Display`) adds its controls to the page,
subscribes the topics it needs on the viewer node and draws into the scene when the viewer
updates it, inside the one batched scene update of that cycle. The frames, the TF buffer and
the time are shared by every display (:class:`~amr_description.web.displays.base.FrameManager`,
RViz's frame manager). ``nodes/viewer.py`` composes them.
"""
