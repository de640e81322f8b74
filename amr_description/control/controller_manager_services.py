# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Controller-manager service client shared by the spawner and ``ros2 control``.

As ros2_control's ``controller_manager/controller_manager_services.py`` (jazzy): one function
per controller-manager service (``list_controllers(node, cm)``, ``switch_controllers(...)``,
...), all going through :func:`service_caller`, which waits for the service (forever when
``service_timeout`` is 0, logging every 10 s), calls it, and retries up to ``max_attempts``
times when no answer arrives within ``call_timeout`` seconds. Also the controller-manager name
resolution and the setting of ``<controller>.<parameter>`` on the manager (``params_file``,
``type``, ``node_options_args``) that the spawner does before loading.

The calls spin ``node`` with an executor of its own context, so they work with a node of a
private :class:`rclpy.context.Context` (the ``ros2`` CLI) as well as the default one.
"""

import time

STRICT = 2
BEST_EFFORT = 1
DISCOVERY_GRACE = 3.0
"""Seconds a new node waits silently for a service to be discovered before saying it waits
(discovery measured here: 0.3 to 2.7 s on a loaded 2-core machine)."""


class bcolors:  # noqa: N801 - the upstream name, imported by the CLI verbs
    """ANSI colours used in upstream's CLI output (see :func:`colors`)."""

    MAGENTA = '\033[95m'
    OKBLUE = '\033[94m'
    OKCYAN = '\033[96m'
    OKGREEN = '\033[92m'
    WARNING = '\033[93m'
    FAIL = '\033[91m'
    ENDC = '\033[0m'
    BOLD = '\033[1m'
    UNDERLINE = '\033[4m'


class _NoColors:
    MAGENTA = OKBLUE = OKCYAN = OKGREEN = WARNING = FAIL = ENDC = BOLD = UNDERLINE = ''


def colors(stream=None):
    """
    Return :class:`bcolors` when ``stream`` (default stdout) is a terminal, else no colours.

    Upstream always prints the escape codes; we print them only to a terminal so that piped
    output and logs stay plain text.
    """
    import sys
    stream = sys.stdout if stream is None else stream
    return bcolors if stream.isatty() else _NoColors


class ServiceNotFoundError(Exception):
    """The controller manager did not offer a service within ``service_timeout``."""


def resolve_controller_manager(node, name):
    """
    Return the absolute name of controller manager ``name`` as seen from ``node``.

    A relative name is resolved in the node's namespace (``-c controller_manager`` from a
    node in ``/r1`` gives ``/r1/controller_manager``), as upstream's service caller does.

    :param node: an rclpy node.
    :param name: absolute or relative node name.
    :returns: the absolute name (str).
    """
    if name.startswith('/'):
        return name
    namespace = node.get_namespace()
    return f'{namespace.rstrip("/")}/{name}' if namespace not in ('', '/') else f'/{name}'


def _executor(node):
    executor = getattr(node, '_cli_executor', None)
    if executor is None:
        from rclpy.executors import SingleThreadedExecutor
        executor = SingleThreadedExecutor(context=node.context)
        executor.add_node(node)
        node._cli_executor = executor
    return executor


def _spin_until(node, predicate, timeout):
    executor = _executor(node)
    deadline = None if timeout is None else time.monotonic() + timeout
    while not predicate():
        if deadline is not None and time.monotonic() >= deadline:
            return False
        step = 0.1 if deadline is None else max(0.0, min(0.1, deadline - time.monotonic()))
        executor.spin_once(timeout_sec=step)
    return True


def service_caller(node, service_name, service_type, request, service_timeout=0.0,
                   call_timeout=10.0, max_attempts=3):
    """
    Call a controller-manager service and return its response.

    :param node: the calling rclpy node (spun here).
    :param service_name: service name; a relative one is resolved in the node's namespace.
    :param service_type: service class, e.g. ``controller_manager_msgs.srv.ListControllers``.
    :param request: the request message.
    :param service_timeout: seconds to wait for the service; 0 waits forever, logging
        "waiting for service ... to become available..." and every 10 s "Could not contact".
    :param call_timeout: seconds to wait for each response.
    :param max_attempts: calls without an answer before giving up.
    :returns: the response message. A node with a ``service_relay`` attribute (the ``ros2``
        CLI's, ``amr_description.cli.daemon.service_relay``) has the call made by it first;
        when it cannot, the node calls itself.
    :raises ServiceNotFoundError: "Could not contact service NAME" after ``service_timeout``.
    :raises RuntimeError: "Could not successfully call service NAME after N attempts.".
    """
    name = resolve_controller_manager(node, service_name)
    relay = getattr(node, 'service_relay', None)  # the ros2 CLI's daemon, when one runs
    if relay is not None:
        response = relay(name, service_type, request, call_timeout)
        if response is not None:
            return response
    client = node.create_client(service_type, name)
    try:
        # a new node needs discovery before any service is ready (ros2cli's direct node
        # spins for its spin time first): no "waiting" line for a service that exists
        _spin_until(node, client.service_is_ready,
                    min(DISCOVERY_GRACE, service_timeout) if service_timeout else DISCOVERY_GRACE)
        while not client.service_is_ready():
            node.get_logger().info(f'waiting for service {name} to become available...')
            wait = service_timeout if service_timeout else 10.0
            if not _spin_until(node, client.service_is_ready, wait):
                if service_timeout:
                    raise ServiceNotFoundError(f'Could not contact service {name}')
                node.get_logger().warn(f'Could not contact service {name}')
        for attempt in range(max_attempts):
            future = client.call_async(request)
            _spin_until(node, future.done, call_timeout)
            if future.done() and future.result() is not None:
                return future.result()
            future.cancel()
            node.get_logger().warn(
                f'Failed getting a result from calling {name} in {call_timeout}. '
                f'(Attempt {attempt + 1} of {max_attempts}.)')
        raise RuntimeError(
            f'Could not successfully call service {name} after {max_attempts} attempts.')
    finally:
        node.destroy_client(client)


def _srv():
    from controller_manager_msgs import srv
    return srv


def _simple(verb, kind_name, **fields):
    def call(node, controller_manager_name, service_timeout=0.0, call_timeout=10.0):
        kind = getattr(_srv(), kind_name)
        request = kind.Request(**fields)
        return service_caller(node, f'{controller_manager_name}/{verb}', kind, request,
                              service_timeout, call_timeout)
    return call


def _named(verb, kind_name):
    def call(node, controller_manager_name, name, service_timeout=0.0, call_timeout=10.0):
        kind = getattr(_srv(), kind_name)
        return service_caller(node, f'{controller_manager_name}/{verb}', kind,
                              kind.Request(name=name), service_timeout, call_timeout)
    return call


list_controllers = _simple('list_controllers', 'ListControllers')
list_controllers.__doc__ = 'Call ``<cm>/list_controllers``; returns the response.'
list_controller_types = _simple('list_controller_types', 'ListControllerTypes')
list_controller_types.__doc__ = 'Call ``<cm>/list_controller_types``; returns the response.'
list_hardware_components = _simple('list_hardware_components', 'ListHardwareComponents')
list_hardware_components.__doc__ = ('Call ``<cm>/list_hardware_components``; returns the '
                                    'response.')
list_hardware_interfaces = _simple('list_hardware_interfaces', 'ListHardwareInterfaces')
list_hardware_interfaces.__doc__ = ('Call ``<cm>/list_hardware_interfaces``; returns the '
                                    'response.')
load_controller = _named('load_controller', 'LoadController')
load_controller.__doc__ = 'Call ``<cm>/load_controller`` for controller ``name``.'
configure_controller = _named('configure_controller', 'ConfigureController')
configure_controller.__doc__ = 'Call ``<cm>/configure_controller`` for controller ``name``.'
cleanup_controller = _named('cleanup_controller', 'CleanupController')
cleanup_controller.__doc__ = 'Call ``<cm>/cleanup_controller`` for controller ``name``.'
unload_controller = _named('unload_controller', 'UnloadController')
unload_controller.__doc__ = 'Call ``<cm>/unload_controller`` for controller ``name``.'


def reload_controller_libraries(node, controller_manager_name, force_kill, service_timeout=0.0,
                                call_timeout=10.0):
    """Call ``<cm>/reload_controller_libraries`` (``force_kill`` unloads controllers first)."""
    kind = _srv().ReloadControllerLibraries
    return service_caller(node, f'{controller_manager_name}/reload_controller_libraries', kind,
                          kind.Request(force_kill=bool(force_kill)), service_timeout,
                          call_timeout)


def set_hardware_component_state(node, controller_manager_name, component_name,
                                 lifecycle_state, service_timeout=0.0, call_timeout=10.0):
    """
    Call ``<cm>/set_hardware_component_state``.

    :param lifecycle_state: a ``lifecycle_msgs/State`` (id and label of the target).
    """
    kind = _srv().SetHardwareComponentState
    request = kind.Request(name=component_name, target_state=lifecycle_state)
    return service_caller(node, f'{controller_manager_name}/set_hardware_component_state',
                          kind, request, service_timeout, call_timeout)


def switch_controllers(node, controller_manager_name, deactivate_controllers,
                       activate_controllers, strict, activate_asap, timeout,
                       call_timeout=10.0):
    """
    Call ``<cm>/switch_controller``.

    :param strict: True for STRICT (2), False for BEST_EFFORT (1).
    :param activate_asap: the request's ``activate_asap``.
    :param timeout: the request's switch timeout, seconds (float); the call itself waits
        ``call_timeout`` plus this.
    """
    from builtin_interfaces.msg import Duration
    kind = _srv().SwitchController
    timeout = float(timeout)
    sec = int(timeout)
    request = kind.Request(
        activate_controllers=list(activate_controllers),
        deactivate_controllers=list(deactivate_controllers),
        strictness=STRICT if strict else BEST_EFFORT, activate_asap=bool(activate_asap),
        timeout=Duration(sec=sec, nanosec=int(round((timeout - sec) * 1e9)) % 1_000_000_000))
    return service_caller(node, f'{controller_manager_name}/switch_controller', kind, request,
                          call_timeout=call_timeout + timeout)


def set_controller_parameter(node, controller_manager_name, controller_name, parameter_name,
                             value, call_timeout=10.0):
    """
    Set ``<controller_name>.<parameter_name>`` on the controller manager.

    As upstream's ``set_controller_parameters``: a str is sent as a string, a list of str as
    a string array (``params_file``, ``node_options_args``). Logs "Setting controller param
    "P" to "V" for C" on success and a fatal line otherwise.

    :returns: True when the manager accepted the value.
    """
    from rcl_interfaces.msg import Parameter
    from rcl_interfaces.msg import ParameterType
    from rcl_interfaces.msg import ParameterValue
    from rcl_interfaces.srv import SetParameters
    if isinstance(value, (list, tuple)):
        pvalue = ParameterValue(type=ParameterType.PARAMETER_STRING_ARRAY,
                                string_array_value=[str(v) for v in value])
        shown = str([str(v) for v in value])
    else:
        pvalue = ParameterValue(type=ParameterType.PARAMETER_STRING, string_value=str(value))
        shown = str(value)
    request = SetParameters.Request(
        parameters=[Parameter(name=f'{controller_name}.{parameter_name}', value=pvalue)])
    response = service_caller(node, f'{controller_manager_name}/set_parameters', SetParameters,
                              request, 10.0, call_timeout)
    ok = bool(response.results) and response.results[0].successful
    if ok:
        node.get_logger().info(f'Setting controller param "{parameter_name}" to "{shown}" for '
                               f'{controller_name}')
    else:
        node.get_logger().fatal(f'Could not set controller param "{parameter_name}" to '
                                f'"{shown}" for {controller_name}')
    return ok
