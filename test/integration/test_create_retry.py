# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``create`` sends its spawn request again when no answer came (a request lost in discovery).

A stand-in spawn service in this process loses the first request (never answers it):
``create`` warns once, as upstream's spawner does, sends the request again and exits 0 with
the second answer. When the first request was carried out but its answer lost, the repeated
request is refused because the name exists: ``create`` reports the entity as created (with a
note) instead of failing.
"""

import os

import pytest
from stand_in import StandIn  # noqa: I100 - helpers next to this file

pytest.importorskip('rclpy')

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
URDF_PATH = os.path.join(ROOT, 'urdf', 'amr.urdf')
SERVICE = '/stand_in/spawn_entity'


class StandInSpawner(StandIn):
    """A SpawnEntity service that never answers the first request it receives."""

    def __init__(self, domain_id, carry_out_first):
        from rclpy.callback_groups import ReentrantCallbackGroup
        from rclpy.task import Future
        from simulation_interfaces.srv import SpawnEntity

        super().__init__('stand_in', domain_id)
        self.Future, self.SpawnEntity = Future, SpawnEntity
        self.carry_out_first = carry_out_first
        self.requests = 0
        self.entities = set()
        # reentrant: the unanswered first request must not hold back the next one
        self.node.create_service(SpawnEntity, SERVICE, self._on_spawn,
                                 callback_group=ReentrantCallbackGroup())
        self.start()

    async def _on_spawn(self, request, response):
        self.requests += 1
        result = response.result
        if request.name in self.entities:
            result.result = self.SpawnEntity.Response.NAME_NOT_UNIQUE
            result.error_message = f'entity {request.name!r} already exists'
            return response
        if self.requests == 1:
            if self.carry_out_first:
                self.entities.add(request.name)
            await self.Future()  # never done: this answer is lost
        self.entities.add(request.name)
        result.result = result.RESULT_OK
        response.entity_name = request.name
        return response


@pytest.mark.parametrize('carry_out_first, note', [
    (False, ''),
    (True, ' (the answer to the first request was lost; the entity exists)'),
])
def test_create_sends_a_lost_request_again(procs, exe, ros_env, carry_out_first, note):
    pytest.importorskip('simulation_interfaces.srv')
    server = StandInSpawner(int(ros_env['ROS_DOMAIN_ID']), carry_out_first)
    try:
        proc = procs.start([exe('create'), '-file', URDF_PATH, '-name', 'amr',
                            '-service', SERVICE], ros_env)
        assert proc.wait(120) == 0, proc.output
        warnings = [line for line in proc.output.splitlines() if '[WARN]' in line]
        assert len(warnings) == 1, proc.output
        assert f'Failed getting a result from calling {SERVICE} in 10 s. (Attempt 1.)' \
            in warnings[0]
        assert proc.output.rstrip().endswith(f'OK creation of entity [amr].{note}'), proc.output
        assert server.requests == 2
    finally:
        server.close()


def test_create_with_allow_renaming_does_not_repeat(procs, exe, ros_env):
    # a repeated request with -allow_renaming could create a second robot: never sent
    pytest.importorskip('simulation_interfaces.srv')
    server = StandInSpawner(int(ros_env['ROS_DOMAIN_ID']), True)
    try:
        proc = procs.start([exe('create'), '-file', URDF_PATH, '-allow_renaming',
                            '-service', SERVICE, '-timeout', '5'], ros_env)
        assert proc.wait(120) == 1, proc.output
        assert f'no answer from {SERVICE}' in proc.output and '[WARN]' not in proc.output
        assert server.requests == 1
    finally:
        server.close()
