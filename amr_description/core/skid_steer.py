# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Coulomb-friction model of a four-wheeled skid-steer base (pure, no rclpy).

Model (the classical skid-steer analysis: J. Y. Wong, *Theory of Ground Vehicles*, skid
steering chapter; K. Kozłowski and D. Pazderski, "Modeling and control of a 4-wheel
skid-steering mobile robot", Int. J. Appl. Math. Comput. Sci. 14(4), 2004): a rigid body
moving in the plane on four point contacts at ``(±a, ±b)`` in the base frame (REP 103: x
forward, y left, z up; ``a`` half the wheelbase, ``b`` half the track), each carrying an
equal normal load ``N = m g / 4`` (centre of mass at the centre, no load transfer). A wheel of
rim speed ``v_i`` (``wheel angular velocity * radius``) sliding over the ground with slip
velocity ``s_i`` = contact-point velocity of the body minus the rim velocity ``(v_i, 0)``
receives the Coulomb force ``F_i = -mu N s_i / |s_i|`` (isotropic friction, no rolling
resistance, no torsional friction).

Turning in place (``v_left = -v``, ``v_right = v``), symmetry gives zero translation and the
yaw moment vanishes when ``omega (a^2 + b^2) = v b`` for every wheel, so
``omega = v b / (a^2 + b^2)``: the two-wheel rate ``v / b`` times ``b^2 / (a^2 + b^2)``. A
differential-drive odometry with the true track ``2 b`` therefore needs
``wheel_separation_multiplier = (a^2 + b^2) / b^2`` (2.78 for a = 0.2 m, b = 0.15 m).
"""

import math

import numpy as np

GRAVITY = 9.81  # m/s^2


def turn_in_place_rate(rim_speed, half_wheelbase, half_track):
    """
    Return the Coulomb turn-in-place yaw rate ``omega = v b / (a^2 + b^2)``.

    :param rim_speed: right-side rim speed ``v`` in m/s (left side at ``-v``); CCW positive.
    :param half_wheelbase: ``a`` in m (>= 0).
    :param half_track: ``b`` in m (> 0).
    :returns: yaw rate in rad/s (float).
    :raises ValueError: when ``b`` is not positive or ``a`` is negative.
    """
    _check_geometry(half_wheelbase, half_track)
    return rim_speed * half_track / (half_wheelbase ** 2 + half_track ** 2)


def geometric_separation_multiplier(half_wheelbase, half_track):
    """
    Return the ``wheel_separation_multiplier`` implied by Coulomb friction, ``(a^2+b^2)/b^2``.

    With it, diff_drive_controller's odometry ``omega = (v_r - v_l) / (2 b k)`` equals the
    turn-in-place rate of :func:`turn_in_place_rate`.

    :param half_wheelbase: ``a`` in m (>= 0).
    :param half_track: ``b`` in m (> 0).
    :returns: the multiplier (float, >= 1).
    :raises ValueError: as :func:`turn_in_place_rate`.
    """
    _check_geometry(half_wheelbase, half_track)
    return (half_wheelbase ** 2 + half_track ** 2) / half_track ** 2


def _check_geometry(half_wheelbase, half_track):
    if not half_track > 0.0:
        raise ValueError(f'half_track must be > 0 m, got {half_track}')
    if not half_wheelbase >= 0.0:
        raise ValueError(f'half_wheelbase must be >= 0 m, got {half_wheelbase}')


def contact_forces(twist, rim_speeds, half_wheelbase, half_track, normal_load, mu,
                   slip_epsilon=1e-4):
    """
    Return the Coulomb forces of the four wheels, their net force and yaw moment.

    :param twist: ``(vx, vy, omega)`` of the base in its own frame (m/s, m/s, rad/s).
    :param rim_speeds: ``(front_left, back_left, front_right, back_right)`` rim speeds, m/s.
    :param half_wheelbase: ``a`` in m.
    :param half_track: ``b`` in m.
    :param normal_load: ``N`` per wheel in newtons.
    :param mu: Coulomb friction coefficient.
    :param slip_epsilon: slip speed in m/s below which the force fades out
        (``F = -mu N s / sqrt(|s|^2 + eps^2)``), which keeps the model continuous at zero slip.
    :returns: ``(forces (4, 2) N in the base frame, net force (2,) N, yaw moment N m,
        jacobian (3, 3))``; the jacobian is d(Fx, Fy, moment)/d(vx, vy, omega).
    """
    vx, vy, omega = (float(v) for v in twist)
    forces = np.empty((4, 2))
    jacobian = np.zeros((3, 3))
    fx_sum = fy_sum = moment = 0.0
    for i, (x, y) in enumerate(_wheel_positions(half_wheelbase, half_track)):
        sx = vx - omega * y - float(rim_speeds[i])
        sy = vy + omega * x
        norm = math.sqrt(sx * sx + sy * sy + slip_epsilon * slip_epsilon)
        k = mu * normal_load / norm
        fx, fy = -k * sx, -k * sy
        forces[i] = fx, fy
        fx_sum += fx
        fy_sum += fy
        moment += x * fy - y * fx
        # dF/ds = -k (I - s s^T / norm^2); ds/d(vx, vy, omega) = [[1, 0, -y], [0, 1, x]]
        c = 1.0 / (norm * norm)
        dfds = -k * np.array([[1.0 - c * sx * sx, -c * sx * sy],
                              [-c * sx * sy, 1.0 - c * sy * sy]])
        dfdu = dfds @ np.array([[1.0, 0.0, -y], [0.0, 1.0, x]])
        jacobian[0:2] += dfdu
        jacobian[2] += x * dfdu[1] - y * dfdu[0]
    return forces, np.array([fx_sum, fy_sum]), moment, jacobian


def _wheel_positions(half_wheelbase, half_track):
    """Return the contact points (front_left, back_left, front_right, back_right), m."""
    a, b = half_wheelbase, half_track
    return ((a, b), (-a, b), (a, -b), (-a, -b))


def integrate_skid_steer(v_left, v_right, half_wheelbase, half_track, mass, yaw_inertia,
                         mu=1.0, duration=3.0, dt=0.005, twist0=(0.0, 0.0, 0.0)):
    """
    Integrate the planar rigid-body motion of a skid-steer base on four Coulomb contacts.

    Equations (base frame, constant rim speeds): ``m (dvx/dt - omega vy) = sum Fx``,
    ``m (dvy/dt + omega vx) = sum Fy``, ``I domega/dt = sum (x Fy - y Fx)``, with the forces of
    :func:`contact_forces` and ``N = m g / 4``; the pose ``(x, y, yaw)`` in the start frame
    follows the twist. Integrated with implicit (backward) Euler steps solved by Newton's
    method with step halving, so the stiff near-zero-slip region stays stable with large
    steps; the motion converges to the steady motion the wheels impose.

    :param v_left: rim speed of both left wheels, m/s.
    :param v_right: rim speed of both right wheels, m/s.
    :param half_wheelbase: ``a`` in m (>= 0).
    :param half_track: ``b`` in m (> 0).
    :param mass: base mass in kg (> 0).
    :param yaw_inertia: moment of inertia about z in kg m^2 (> 0).
    :param mu: Coulomb friction coefficient (> 0).
    :param duration: simulated time in s.
    :param dt: integration step in s.
    :param twist0: initial ``(vx, vy, omega)``.
    :returns: ``(times (n,), twists (n, 3), poses (n, 3))``; twists in the base frame
        (m/s, m/s, rad/s), poses ``(x, y, yaw)`` in m, m, rad, starting at the origin.
    :raises ValueError: when a physical parameter is not positive.
    """
    _check_geometry(half_wheelbase, half_track)
    for name, value in (('mass', mass), ('yaw_inertia', yaw_inertia), ('mu', mu), ('dt', dt)):
        if not value > 0.0:
            raise ValueError(f'{name} must be > 0, got {value}')
    rims = (v_left, v_left, v_right, v_right)
    load = mass * GRAVITY / 4.0
    inertia = np.array([mass, mass, yaw_inertia])

    def residual(u, previous):
        """Return the implicit Euler residual and its jacobian."""
        _, force, moment, jac = contact_forces(u, rims, half_wheelbase, half_track, load, mu)
        vx, vy, omega = u
        rate = np.array([force[0] + mass * omega * vy, force[1] - mass * omega * vx, moment])
        jac = jac + np.array([[0.0, mass * omega, mass * vy],
                              [-mass * omega, 0.0, -mass * vx], [0.0, 0.0, 0.0]])
        res = inertia * (u - previous) - dt * rate
        return res, np.diag(inertia) - dt * jac

    steps = max(1, int(round(duration / dt)))
    times = np.arange(steps + 1) * dt
    twists = np.empty((steps + 1, 3))
    poses = np.zeros((steps + 1, 3))
    twists[0] = twist0
    for k in range(1, steps + 1):
        previous = twists[k - 1]
        u = previous.copy()
        res, jac = residual(u, previous)
        for _ in range(30):
            size = float(np.linalg.norm(res))
            if size < 1e-10 * mass:
                break
            delta = np.linalg.solve(jac, -res)
            scale = 1.0
            while True:  # halve the Newton step until the residual shrinks
                candidate = u + scale * delta
                cand_res, cand_jac = residual(candidate, previous)
                if np.linalg.norm(cand_res) < size or scale < 1e-3:
                    break
                scale *= 0.5
            u, res, jac = candidate, cand_res, cand_jac
        yaw = poses[k - 1, 2]
        poses[k] = poses[k - 1] + dt * np.array([u[0] * math.cos(yaw) - u[1] * math.sin(yaw),
                                                 u[0] * math.sin(yaw) + u[1] * math.cos(yaw),
                                                 u[2]])
        twists[k] = u
    return times, twists, poses


def steady_twist(v_left, v_right, half_wheelbase, half_track, mass, yaw_inertia, mu=1.0):
    """
    Return the steady base twist ``(vx, vy, omega)`` for constant rim speeds.

    The end state of :func:`integrate_skid_steer` from rest after 2 s (a robot-sized base
    reaches its steady motion within a few tenths of a second: the friction acceleration is
    about ``mu g``).

    :returns: numpy array (3,): m/s, m/s, rad/s in the base frame.
    :raises ValueError: as :func:`integrate_skid_steer`.
    """
    _, twists, _ = integrate_skid_steer(v_left, v_right, half_wheelbase, half_track, mass,
                                        yaw_inertia, mu=mu, duration=2.0, dt=0.01)
    return twists[-1]
