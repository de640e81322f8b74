# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Local world coordinates to latitude, longitude and altitude on the WGS84 ellipsoid.

What gz-sim's NavSat system does with a world's ``<spherical_coordinates>`` (gz-math
``SphericalCoordinates``): the world origin sits at ``latitude_deg``, ``longitude_deg`` and
``elevation`` (m above the ellipsoid); the world's x, y, z are east, north, up (``ENU``)
turned by ``heading_deg`` (SDF: the angle from the ENU frame to the world frame, positive
about the downward vertical, so a positive heading turns the world's x axis from east towards
south). A local point goes to Earth-centred, Earth-fixed coordinates through the origin's
ENU axes and back to geodetic ones (WGS84: a = 6378137 m, f = 1 / 298.257223563; NIMA
TR8350.2). Angles in degrees, lengths in metres.
"""

from dataclasses import dataclass
import math

WGS84_A = 6378137.0
"""m, the ellipsoid's equatorial radius."""
WGS84_F = 1.0 / 298.257223563
"""The ellipsoid's flattening."""
WGS84_E2 = WGS84_F * (2.0 - WGS84_F)
"""The first eccentricity squared."""


@dataclass
class SphericalCoordinates:
    """
    A world's ``<spherical_coordinates>`` (SDF 1.11 ``spherical_coordinates.sdf``).

    :param latitude_deg: of the world origin (deg, -90..90).
    :param longitude_deg: of the world origin (deg).
    :param elevation: m above the WGS84 ellipsoid.
    :param heading_deg: deg (module docstring).
    """

    latitude_deg: float = 0.0
    longitude_deg: float = 0.0
    elevation: float = 0.0
    heading_deg: float = 0.0


def geodetic_to_ecef(latitude_deg, longitude_deg, altitude):
    """Return the ECEF (x, y, z) in m of a geodetic point (deg, deg, m)."""
    lat, lon = math.radians(latitude_deg), math.radians(longitude_deg)
    n = WGS84_A / math.sqrt(1.0 - WGS84_E2 * math.sin(lat) ** 2)
    return ((n + altitude) * math.cos(lat) * math.cos(lon),
            (n + altitude) * math.cos(lat) * math.sin(lon),
            (n * (1.0 - WGS84_E2) + altitude) * math.sin(lat))


def ecef_to_geodetic(x, y, z):
    """
    Return (latitude deg, longitude deg, altitude m) of an ECEF point (m).

    Fixed-point iteration on the latitude (converges to 1e-12 rad in a few steps near the
    surface).
    """
    lon = math.atan2(y, x)
    p = math.hypot(x, y)
    lat = math.atan2(z, p * (1.0 - WGS84_E2))
    altitude = 0.0
    for _ in range(20):
        n = WGS84_A / math.sqrt(1.0 - WGS84_E2 * math.sin(lat) ** 2)
        altitude = p / math.cos(lat) - n if abs(lat) < math.pi / 4 else \
            z / math.sin(lat) - n * (1.0 - WGS84_E2)
        new = math.atan2(z, p * (1.0 - WGS84_E2 * n / (n + altitude)))
        if abs(new - lat) < 1e-13:
            lat = new
            break
        lat = new
    return math.degrees(lat), math.degrees(lon), altitude


def local_to_geodetic(origin, x, y, z):
    """
    Return (latitude deg, longitude deg, altitude m) of world point (x, y, z) m.

    :param origin: the world's :class:`SphericalCoordinates`.
    """
    heading = math.radians(origin.heading_deg)
    east = x * math.cos(heading) + y * math.sin(heading)
    north = -x * math.sin(heading) + y * math.cos(heading)
    lat, lon = math.radians(origin.latitude_deg), math.radians(origin.longitude_deg)
    x0, y0, z0 = geodetic_to_ecef(origin.latitude_deg, origin.longitude_deg, origin.elevation)
    sl, cl, so, co = math.sin(lat), math.cos(lat), math.sin(lon), math.cos(lon)
    ex = -so * east - sl * co * north + cl * co * z
    ey = co * east - sl * so * north + cl * so * z
    ez = cl * north + sl * z
    return ecef_to_geodetic(x0 + ex, y0 + ey, z0 + ez)
