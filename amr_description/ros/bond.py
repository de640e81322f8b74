# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A bond as ros/bond_core's bondcpp makes one: two processes watching each other's heartbeats.

Each side publishes ``bond/msg/Status`` on the bond topic (``bond`` for Nav2; keep-last 5,
reliable) every heartbeat period with its bond ``id`` (Nav2: the managed node's name), its own
``instance_id`` (a random UUID), ``active`` true, and its heartbeat timeout and period; it
subscribes to the same topic (depth 100). The bond is *formed* when a status with the same
``id`` and another ``instance_id`` arrives (bondcpp's ``SisterAlive`` in state
``WaitingForSister``). It is *broken* when the other side says ``active`` false, when no status
of the other side arrived for ``heartbeat_timeout`` (unless the node's parameter
``bond_disable_heartbeat_timeout`` is true); this side then says ``active`` false in its next
few heartbeats. :meth:`Bond.destroy` says it once and removes the bond.

All bonds of a node on one topic share one publisher and one subscription, made by the first
bond or earlier by :func:`prepare_bonds` (a lifecycle manager and a managed node at start-up,
a node whose bond depends on its parameters at configure), so that DDS has matched them with the
other side long before a bond must form within its timeout (bondcpp makes them per bond; on a
loaded machine, the Python processes' discovery of endpoints made at activation took over
Nav2's 2 s). The endpoint also keeps the
last status heard for each id, so a bond started within a second after its sister's first
heartbeat forms on that heartbeat (bondcpp drops statuses heard before its bond starts and waits
for the next one, which on a loaded machine came 0.5 s later in one measured bring-up).
Source: ``bondcpp/src/bond.cpp`` and ``bond/msg/Constants.msg`` of ros/bond_core (ros2 branch).
"""

import threading
import uuid

from amr_description.ros.cdr import bond_status
from amr_description.ros.cdr import read
from amr_description.ros.take_loop import TakeLoop
from bond.msg import Constants
from bond.msg import Status
from rclpy.clock import Clock
from rclpy.clock import ClockType
from rclpy.qos import QoSProfile

DISABLE_PARAM = 'bond_disable_heartbeat_timeout'
"""The node parameter that disables the heartbeat timeout (``Constants``' name for it)."""

DEAD_REPEATS = 3
"""How many ``active: false`` statuses a broken bond still publishes."""

RECENT = 1.0
"""Seconds for which a status heard before a bond started still forms it."""

_ENDPOINTS = '_amr_bond_endpoints'
"""The node attribute holding its :class:`_Endpoint` per bond topic."""

_HEARTS = '_amr_bond_hearts'
"""The node attribute holding its :class:`_Heart` per heartbeat period."""

_PROCESS_ENDPOINTS = {}
"""(context id, resolved topic) -> :class:`_Endpoint` once :func:`share_endpoints` was called."""

_sharing = []


class _Endpoint:
    """
    The publisher and subscription a node's bonds on one topic share.

    The statuses are taken serialized on a :class:`~amr_description.ros.take_loop.TakeLoop`
    of their own, not by the node's executor: a composed Nav2 hears about 165 statuses a
    second (docs/navigation.md, "The bonds' and the odometry's threads"). The heartbeats stay
    on the bonds' nodes' executors, as bondcpp's timers, so a node whose executor stops stops
    beating.
    """

    def __init__(self, node, topic):
        self.bonds = set()
        self.last = {}  # id -> (steady seconds heard, the latest status of that id)
        self.lock = threading.Lock()
        self.clock = Clock(clock_type=ClockType.STEADY_TIME)
        self.publisher = node.create_publisher(Status, topic, QoSProfile(depth=5))
        self._loop = TakeLoop(node, f'{node.get_name()}_bond')
        self._loop.subscribe(Status, topic, 100, self._on_data)
        self._loop.start()

    def now(self):
        return self.clock.now().nanoseconds * 1e-9

    def _on_data(self, data):
        self._on_status(read(data, bond_status, Status))

    def _on_status(self, msg):
        with self.lock:
            self.last[msg.id] = (self.now(), msg)
            bonds = list(self.bonds)
        for bond in bonds:
            bond.on_status(msg)

    def add(self, bond):
        """Register ``bond``; an active status of its id heard just before forms it."""
        with self.lock:
            self.bonds.add(bond)
            heard, msg = self.last.get(bond.id, (None, None))
        if msg is not None and msg.active and self.now() - heard <= RECENT:
            bond.on_status(msg)


class _Heart:
    """
    One timer on a node beating all of that node's bonds of one period.

    bondcpp makes a timer per bond; a lifecycle manager of seven servers then woke its
    executor 70 times a second for them. The beats are the same (each bond publishes its
    status every period), only in one wake-up.
    """

    def __init__(self, node, period):
        self.bonds = []
        self.timer = node.create_timer(period, self._beat)

    def _beat(self):
        for bond in list(self.bonds):
            bond._tick()


def share_endpoints():
    """
    From now on, let the nodes of this process share one endpoint per resolved bond topic.

    For a container whose nodes live as long as the process (the first node to prepare a
    topic owns the endpoint's publisher and subscription, spun by that node's executor).
    Each status on the topic is then taken once by the process instead of once per node:
    in Nav2's composed bring-up, 8 managed nodes and 2 lifecycle managers exchange 160
    statuses a second, and every subscriber's executor woke for each of them
    (docs/navigation.md, "Composition"). On the wire nothing changes: the same statuses, ids,
    periods and QoS.
    """
    _sharing.append(True)


def prepare_bonds(node, topic):
    """
    Return the bond endpoint of ``node`` on ``topic``, made now if it does not exist.

    :param node: an rclpy node.
    :param topic: the bond topic (Nav2: ``bond``).
    :returns: the node's endpoint, or the process's one after :func:`share_endpoints`.
    """
    endpoints = node.__dict__.setdefault(_ENDPOINTS, {})
    if topic not in endpoints:
        key = (id(node.context), node.resolve_topic_name(topic))
        endpoint = _PROCESS_ENDPOINTS.get(key) if _sharing else None
        if endpoint is None:
            endpoint = _Endpoint(node, topic)
            if _sharing:
                _PROCESS_ENDPOINTS[key] = endpoint
        endpoints[topic] = endpoint
    return endpoints[topic]


class Bond:
    """
    One side of a bond on ``node``, started at construction.

    :param node: the rclpy node whose timers and topics the bond uses.
    :param topic: the bond topic (Nav2: ``bond``).
    :param bond_id: the bond's id (Nav2: the managed node's name).
    :param heartbeat_period: seconds between status messages.
    :param heartbeat_timeout: seconds without the other side's status before the bond breaks.
    """

    def __init__(self, node, topic, bond_id, heartbeat_period=Constants.DEFAULT_HEARTBEAT_PERIOD,
                 heartbeat_timeout=Constants.DEFAULT_HEARTBEAT_TIMEOUT):
        """Create the publisher, the subscription and the heartbeat timer."""
        self._node = node
        self.id = bond_id
        self.instance_id = str(uuid.uuid4())
        self.heartbeat_period = float(heartbeat_period)
        self.heartbeat_timeout = float(heartbeat_timeout)
        if not node.has_parameter(DISABLE_PARAM):
            node.declare_parameter(DISABLE_PARAM, False)
        self._heartbeat_timeout_disabled = bool(node.get_parameter(DISABLE_PARAM).value)
        self._formed = threading.Event()
        self._lock = threading.Lock()  # statuses come on the endpoint's thread
        self.broken = False
        self._sister_seen = None
        self._dead_left = 0
        self._endpoint = prepare_bonds(node, topic)
        hearts = node.__dict__.setdefault(_HEARTS, {})
        if self.heartbeat_period not in hearts:
            hearts[self.heartbeat_period] = _Heart(node, self.heartbeat_period)
        hearts[self.heartbeat_period].bonds.append(self)
        self._publish(True)
        self._endpoint.add(self)

    @property
    def formed(self):
        """Return True once the other side's status was seen."""
        return self._formed.is_set()

    def wait_until_formed(self, timeout):
        """
        Wait until the bond forms (bondcpp's ``waitUntilFormed``), while the node is spun.

        :param timeout: seconds to wait.
        :returns: True when formed.
        """
        return self._formed.wait(timeout)

    def _now(self):
        return self._endpoint.now()

    def _publish(self, active):
        msg = Status()
        msg.header.stamp = self._endpoint.clock.now().to_msg()
        msg.id = self.id
        msg.instance_id = self.instance_id
        msg.active = active
        msg.heartbeat_timeout = self.heartbeat_timeout
        msg.heartbeat_period = self.heartbeat_period
        self._endpoint.publisher.publish(msg)

    def on_status(self, msg):
        """
        Take a status heard on the bond topic (the endpoint's thread calls it).

        :param msg: a ``bond/msg/Status`` or :data:`amr_description.ros.cdr.BondStatus`.
        """
        if msg.id != self.id or msg.instance_id == self.instance_id:
            return
        with self._lock:
            if self.broken:
                return
            if not msg.active:
                self._break()
                return
            self._sister_seen = self._now()
        self._formed.set()

    def _tick(self):
        with self._lock:
            if self.broken:
                if self._dead_left > 0:
                    self._dead_left -= 1
                    self._publish(False)
                return
            self._publish(True)
            if self.formed and not self._heartbeat_timeout_disabled and \
                    self._now() - self._sister_seen > self.heartbeat_timeout:
                self._break()

    def _break(self):
        if not self.broken:
            self.broken = True
            self._dead_left = DEAD_REPEATS

    def destroy(self):
        """Break the bond if it is not, stop its heartbeat and stop hearing statuses."""
        with self._lock:
            if not self.broken:
                self.broken = True
                self._publish(False)
        hearts = self._node.__dict__.get(_HEARTS, {})
        heart = hearts.get(self.heartbeat_period)
        if heart is not None and self in heart.bonds:
            heart.bonds.remove(self)
            if not heart.bonds:
                del hearts[self.heartbeat_period]
                self._node.destroy_timer(heart.timer)
        with self._endpoint.lock:
            self._endpoint.bonds.discard(self)
