# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
spawner: load, configure and activate controllers through controller-manager services.

Command line and log lines as ros2_control's ``controller_manager spawner`` (jazzy)::

    spawner NAME... [-c CM] [-p PARAM_FILE]... [-n NS] [--load-only] [--inactive]
            [-u] [--controller-manager-timeout S] [--switch-timeout S]
            [--service-call-timeout S] [--activate-as-group]
            [--controller-ros-args ARGS]... [--ros-args ...]

For every controller: skipped with a warning when already loaded, else (after setting
``<name>.node_options_args`` from ``--controller-ros-args``, and ``<name>.params_file``/
``<name>.type`` when ``-p`` files mention it, on the manager) loaded ("Loaded NAME");
then configured and activated ("Configured and activated NAME"). Exit code 0 on success,
1 on any failure (one error line, e.g. "Could not contact service
/controller_manager/list_controllers" after ``--controller-manager-timeout`` seconds).
"""

import argparse
import os
import sys
import time

from amr_description.control import controller_manager_services as cms
from amr_description.control.controller_manager_services import ServiceNotFoundError
from amr_description.core import ros_param_file
from amr_description.ros import shutdown
from amr_description.ros.node import Node


STRICT = cms.STRICT
BEST_EFFORT = cms.BEST_EFFORT

__all__ = ['Spawner', 'ServiceNotFoundError', 'main', 'run']


class Spawner(Node):
    """Short-lived node calling controller-manager services."""

    def __init__(self, first_controller, namespace=None):
        """Create node ``spawner_<first_controller>``."""
        kwargs = {'namespace': namespace} if namespace else {}
        super().__init__(f'spawner_{first_controller}', **kwargs)


def _files_for(controller, namespace, files):
    """Return (files mentioning ``controller``, its ``type`` or None)."""
    found, type_name = [], None
    for path in files:
        data = ros_param_file.load_yaml(path)
        params = ros_param_file.parameters_for_node(data, controller, namespace, path)
        if params:
            found.append(path)
            type_name = params.get('type', type_name)
    return found, type_name


def _parser():
    parser = argparse.ArgumentParser(prog='spawner')
    parser.add_argument('controller_names', help='List of controllers', nargs='+')
    parser.add_argument('-c', '--controller-manager', default='controller_manager',
                        help='Name of the controller manager ROS node')
    parser.add_argument('-p', '--param-file', action='append', default=None,
                        help='Controller param file to be loaded into controller node before '
                        'configure. Pass multiple times to load different files.')
    parser.add_argument('-n', '--namespace', default=None,
                        help='DEPRECATED Namespace for the controller_manager and the '
                        'controller(s)')
    parser.add_argument('--load-only', action='store_true',
                        help='Only load the controller and leave unconfigured.')
    parser.add_argument('--inactive', action='store_true',
                        help='Load and configure the controller, however do not activate them')
    parser.add_argument('-u', '--unload-on-kill', action='store_true',
                        help='Wait until this application is interrupted and unload controller')
    parser.add_argument('--controller-manager-timeout', type=float, default=0.0,
                        help='Time to wait for the controller manager service to be available')
    parser.add_argument('--switch-timeout', type=float, default=5.0,
                        help='Time to wait for a successful state switch of controllers.')
    parser.add_argument('--service-call-timeout', type=float, default=10.0,
                        help='Time to wait for the service response from the controller '
                        'manager')
    parser.add_argument('--activate-as-group', action='store_true',
                        help='Activates all the parsed controllers list together instead of '
                        'one by one.')
    parser.add_argument('--controller-ros-args', action='append', default=None,
                        help='The --ros-args to be passed to the controller node, e.g., for '
                        'remapping topics. Pass multiple times for every argument.')
    return parser


def _switch(node, cm, activate, deactivate, timeout, call_timeout):
    return cms.switch_controllers(node, cm, deactivate, activate, True, False, timeout,
                                  call_timeout)


def run(node, args, cm):
    """Spawn every controller of ``args``; returns the exit code."""
    log = node.get_logger()
    names = args.controller_names
    tmo, call_tmo = args.controller_manager_timeout, args.service_call_timeout
    ros_args = [arg for text in (args.controller_ros_args or []) for arg in text.split()]
    for name in names:
        listed = cms.list_controllers(node, cm, tmo, call_tmo)
        loaded = [c for c in listed.controller if c.name == name]
        if loaded:
            log.warn('Controller already loaded, skipping load_controller')
            if loaded[0].state == 'active' and not (args.load_only or args.inactive):
                log.warn(f'Controller {name} is already active, skipping')
                continue
        else:
            if ros_args and not cms.set_controller_parameter(
                    node, cm, name, 'node_options_args', ros_args, call_tmo):
                return 1
            if args.param_file:
                files, type_name = _files_for(name, node.get_namespace(), args.param_file)
                if files:
                    if not cms.set_controller_parameter(node, cm, name, 'params_file', files,
                                                        call_tmo):
                        return 1
                    if type_name and not cms.set_controller_parameter(
                            node, cm, name, 'type', type_name, call_tmo):
                        return 1
            ret = cms.load_controller(node, cm, name, tmo, call_tmo)
            if not ret.ok:
                log.fatal(f'Failed loading controller {name}')
                return 1
            log.info(f'Loaded {name}')
        if args.load_only:
            continue
        ret = cms.configure_controller(node, cm, name, tmo, call_tmo)
        if not ret.ok:
            log.error('Failed to configure controller')
            return 1
        if args.inactive or args.activate_as_group:
            continue
        ret = _switch(node, cm, [name], [], args.switch_timeout, call_tmo)
        if not ret.ok:
            log.error(f'Failed to activate controller : {name}')
            return 1
        log.info(f'Configured and activated {name}')
    if args.activate_as_group and not args.inactive and not args.load_only:
        ret = _switch(node, cm, names, [], args.switch_timeout, call_tmo)
        if not ret.ok:
            log.error(f'Failed to activate the parsed controllers list : {names}')
            return 1
        log.info(f'Configured and activated all the parsed controllers list : {names}!')
    if not args.unload_on_kill:
        return 0
    log.info('Waiting until interrupt to unload controllers')
    try:
        while True:
            time.sleep(1.0)
    except KeyboardInterrupt:
        log.info('KeyboardInterrupt successfully captured!')
        if not args.inactive and not args.load_only:
            log.info('Deactivating and unloading controllers...')
            ret = _switch(node, cm, [], names, args.switch_timeout, call_tmo)
            if not ret.ok:
                log.error('Failed to deactivate controller')
                return 1
            log.info(f'Successfully deactivated controllers : {names}')
        failed = False
        for name in names:
            ret = cms.unload_controller(node, cm, name, tmo, call_tmo)
            if not ret.ok:
                failed = True
                log.error(f'Failed to unload controller : {name}')
        if failed:
            return 1
        log.info(f'Successfully unloaded controllers : {names}')
    return 0


def main(args=None):
    """
    Entry point of ``ros2 run amr_description spawner``; returns the exit code.

    Clean-shutdown pattern of :mod:`amr_description.ros.shutdown` (bad ROS arguments: one
    line, exit code 1).
    """
    argv = sys.argv if args is None else ['spawner'] + list(args)
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    opts = _parser().parse_args(shutdown.remove_ros_args(argv)[1:])
    for path in opts.param_file or []:
        if not os.path.isfile(path):
            print(f'spawner: parameter file {path} not found', file=sys.stderr)
            return 1
    node = None
    code = 1
    try:
        shutdown.init(argv)
        node = shutdown.create(Spawner, opts.controller_names[0], opts.namespace)
        cm = cms.resolve_controller_manager(node, opts.controller_manager)
        code = run(node, opts, cm)
    except KeyboardInterrupt:
        if node is not None:
            node.get_logger().info('KeyboardInterrupt received! Exiting....')
        code = 0
    except (ServiceNotFoundError, RuntimeError, ValueError) as exc:
        if node is not None:
            node.get_logger().fatal(str(exc))
        else:
            print(f'spawner: {exc}', file=sys.stderr)
        code = 1
    finally:
        shutdown.shutdown(node)
    return code


if __name__ == '__main__':
    sys.exit(main())
