# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""What every ``ros2 control`` verb shares: the CLI node, errors, common arguments."""


from amr_description.cli.common import cli_node
from amr_description.cli.common import default_node_name
from amr_description.cli.common import fail
from amr_description.cli.daemon import service_relay
from amr_description.control import controller_manager_services as cms


def node_args(args):
    return ['--ros-args', '-p', 'use_sim_time:=true'] if args.use_sim_time else None


def run(args, body):
    """Run ``body(node, cm)`` with a CLI node; errors of the service layer: one line, 1."""
    try:
        with cli_node(default_node_name(), node_args(args)) as node:
            node.service_relay = service_relay()
            cm = cms.resolve_controller_manager(node, args.controller_manager)
            code = body(node, cm)
            return code if isinstance(code, int) else fail(code)
    except (RuntimeError, cms.ServiceNotFoundError) as exc:
        return fail(str(exc))


def error(message):
    """Print an upstream error line (red on a terminal) to stdout; returns 1."""
    c = cms.colors()
    print(f'{c.FAIL}{message}{c.ENDC}')
    return 1


def common_arguments(parser):
    parser.add_argument('-c', '--controller-manager', default='controller_manager',
                        help='Name of the controller manager ROS node (default: '
                        'controller_manager)')
    parser.add_argument('--include-hidden-nodes', action='store_true',
                        help='Consider hidden nodes as well')
    parser.add_argument('-s', '--use-sim-time', action='store_true',
                        help='Enable ROS simulation time')
    parser.add_argument('--spin-time', type=float, default=0.5,
                        help='Spin time in seconds to wait for discovery')
