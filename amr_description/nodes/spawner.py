# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
spawner: load, configure and activate controllers through controller-manager services.

Command line and log lines as ros2_control's ``controller_manager spawner`` (jazzy)::

    spawner NAME... [-c CM] [-p PARAM_FILE]... [-n NS] [--load-only] [--inactive]
            [-u] [--controller-manager-timeout S] [--switch-timeout S]
            [--service-call-timeout S] [--activate-as-group] [--ros-args ...]

For every controller: skipped with a warning when already loaded, else (after setting
``<name>.params_file``/``<name>.type`` on the manager when ``-p`` files mention it) loaded
("Loaded NAME"); then configured and activated ("Configured and activated NAME"). Exit code
0 on success, 1 on any failure (one error line, e.g. "Could not contact service
/controller_manager/list_controllers" after ``--controller-manager-timeout`` seconds).
"""

import argparse
import os
import sys
import time

from amr_description.core import ros_param_file
import rclpy
from rclpy.node import Node
from rclpy.signals import SignalHandlerOptions

STRICT = 2
BEST_EFFORT = 1


class ServiceNotFoundError(Exception):
    """The controller manager did not offer a service in time."""


class Spawner(Node):
    """Short-lived node calling controller-manager services."""

    def __init__(self, first_controller, namespace=None):
        """Create node ``spawner_<first_controller>``."""
        kwargs = {'namespace': namespace} if namespace else {}
        super().__init__(f'spawner_{first_controller}', **kwargs)

    def call(self, service_name, service_type, request, service_timeout=0.0, call_timeout=10.0,
             attempts=3):
        """
        Call a service and return its response.

        :param service_name: absolute service name.
        :param service_type: service class.
        :param request: request message.
        :param service_timeout: seconds to wait for the service (0: forever, logging every
            10 s).
        :param call_timeout: seconds to wait for each response.
        :param attempts: number of calls before giving up.
        :returns: the response.
        :raises ServiceNotFoundError: when the service does not appear in time.
        :raises RuntimeError: when no response arrives.
        """
        client = self.create_client(service_type, service_name)
        try:
            while not client.service_is_ready():
                self.get_logger().info(f'waiting for service {service_name} to become '
                                       'available...')
                if service_timeout:
                    if not client.wait_for_service(service_timeout):
                        raise ServiceNotFoundError(f'Could not contact service {service_name}')
                elif not client.wait_for_service(10.0):
                    self.get_logger().warn(f'Could not contact service {service_name}')
            for attempt in range(attempts):
                future = client.call_async(request)
                rclpy.spin_until_future_complete(self, future, timeout_sec=call_timeout)
                if future.result() is not None:
                    return future.result()
                self.get_logger().warn(
                    f'Failed getting a result from calling {service_name} in {call_timeout}. '
                    f'(Attempt {attempt + 1} of {attempts}.)')
            raise RuntimeError(f'Could not successfully call service {service_name} after '
                               f'{attempts} attempts.')
        finally:
            self.destroy_client(client)

    def set_cm_parameter(self, cm, name, value):
        """Set string parameter ``name`` on the controller manager; returns True when set."""
        from rcl_interfaces.msg import Parameter
        from rcl_interfaces.msg import ParameterType
        from rcl_interfaces.msg import ParameterValue
        from rcl_interfaces.srv import SetParameters
        request = SetParameters.Request()
        request.parameters = [Parameter(name=name, value=ParameterValue(
            type=ParameterType.PARAMETER_STRING, string_value=str(value)))]
        response = self.call(f'{cm}/set_parameters', SetParameters, request, 10.0)
        ok = bool(response.results) and response.results[0].successful
        controller, _, key = name.partition('.')
        if ok:
            self.get_logger().info(f'Setting controller param "{key}" to "{value}" for '
                                   f'{controller}')
        else:
            self.get_logger().fatal(f'Could not set controller param "{key}" to "{value}" '
                                    f'for {controller}')
        return ok


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
    return parser


def _switch(node, cm, activate, deactivate, timeout, call_timeout):
    from builtin_interfaces.msg import Duration
    from controller_manager_msgs.srv import SwitchController
    request = SwitchController.Request()
    request.activate_controllers = list(activate)
    request.deactivate_controllers = list(deactivate)
    request.strictness = STRICT
    request.activate_asap = False
    request.timeout = Duration(sec=int(timeout), nanosec=int((timeout % 1.0) * 1e9))
    return node.call(f'{cm}/switch_controller', SwitchController, request,
                     call_timeout=call_timeout + timeout)


def run(node, args, cm):
    """Spawn every controller of ``args``; returns the exit code."""
    from controller_manager_msgs import srv
    log = node.get_logger()
    names = args.controller_names
    tmo, call_tmo = args.controller_manager_timeout, args.service_call_timeout
    for name in names:
        listed = node.call(f'{cm}/list_controllers', srv.ListControllers,
                           srv.ListControllers.Request(), tmo, call_tmo)
        loaded = [c for c in listed.controller if c.name == name]
        if loaded:
            log.warn('Controller already loaded, skipping load_controller')
            if loaded[0].state == 'active' and not (args.load_only or args.inactive):
                log.warn(f'Controller {name} is already active, skipping')
                continue
        else:
            if args.param_file:
                files, type_name = _files_for(name, node.get_namespace(), args.param_file)
                if files:
                    if not node.set_cm_parameter(cm, f'{name}.params_file', str(files)):
                        return 1
                    if type_name and not node.set_cm_parameter(cm, f'{name}.type', type_name):
                        return 1
            ret = node.call(f'{cm}/load_controller', srv.LoadController,
                            srv.LoadController.Request(name=name), tmo, call_tmo)
            if not ret.ok:
                log.fatal(f'Failed loading controller {name}')
                return 1
            log.info(f'Loaded {name}')
        if args.load_only:
            continue
        ret = node.call(f'{cm}/configure_controller', srv.ConfigureController,
                        srv.ConfigureController.Request(name=name), tmo, call_tmo)
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
            ret = node.call(f'{cm}/unload_controller', srv.UnloadController,
                            srv.UnloadController.Request(name=name), tmo, call_tmo)
            if not ret.ok:
                failed = True
                log.error(f'Failed to unload controller : {name}')
        if failed:
            return 1
        log.info(f'Successfully unloaded controllers : {names}')
    return 0


def main(args=None):
    """Entry point of ``ros2 run amr_description spawner``; returns the exit code."""
    argv = sys.argv if args is None else ['spawner'] + list(args)
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    rclpy.init(args=argv, signal_handler_options=SignalHandlerOptions.NO)
    opts = _parser().parse_args(rclpy.utilities.remove_ros_args(args=argv)[1:])
    for path in opts.param_file or []:
        if not os.path.isfile(path):
            print(f'spawner: parameter file {path} not found', file=sys.stderr)
            rclpy.try_shutdown()
            return 1
    node = None
    code = 1
    try:
        node = Spawner(opts.controller_names[0], opts.namespace)
        ns = node.get_namespace()
        cm = opts.controller_manager
        if not cm.startswith('/'):
            cm = f'{ns.rstrip("/")}/{cm}' if ns and ns != '/' else f'/{cm}'
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
        if node is not None:
            node.destroy_node()
        rclpy.try_shutdown()
    return code


if __name__ == '__main__':
    sys.exit(main())
