# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The component container imports every listed component's module before creating any."""

from amr_description.nodes.component_container import preload


class _EntryPoint:
    """An entry point whose ``load`` records the call, or fails as an unimportable module."""

    def __init__(self, name, calls, error=None):
        self.name, self.calls, self.error = name, calls, error

    def load(self):
        self.calls.append(self.name)
        if self.error is not None:
            raise self.error
        return object


def test_every_listed_plugin_is_imported_in_the_launch_order():
    calls = []
    plugins = {name: _EntryPoint(name, calls) for name in
               ('nav2_map_server::MapServer', 'nav2_amcl::AmclNode',
                'nav2_lifecycle_manager::LifecycleManager', 'nav2_controller::ControllerServer')}
    plugins['nav2_amcl::AmclNode'].error = ImportError('No module named scipy')
    components = [('nav2_map_server::MapServer', ['--ros-args']),
                  ('nav2_amcl::AmclNode', ['--ros-args']),
                  ('no_such::Plugin', ['--ros-args']),
                  ('nav2_lifecycle_manager::LifecycleManager', ['--ros-args']),
                  ('nav2_controller::ControllerServer', ['--ros-args'])]
    preload(components, plugins)
    # a failed import and an unknown plugin are left to load(), in their turn; the rest go on
    assert calls == ['nav2_map_server::MapServer', 'nav2_amcl::AmclNode',
                     'nav2_lifecycle_manager::LifecycleManager',
                     'nav2_controller::ControllerServer']
