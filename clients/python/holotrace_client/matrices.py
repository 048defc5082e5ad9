"""4x4 world matrices for UpdateScene node edits.

Matrices here are numpy arrays in the usual maths layout, m[row][column], acting on column vectors (translation in the
last column). The protocol wants the 16 values column-major, the order of a glTF node's `matrix`
(NodeTransform.world); world_values() converts.
"""

import math

import numpy as np


def identity():
    return np.eye(4)


def translation(x, y, z):
    m = np.eye(4)
    m[:3, 3] = (x, y, z)
    return m


def scaling(sx, sy=None, sz=None):
    sy = sx if sy is None else sy
    sz = sx if sz is None else sz
    return np.diag([sx, sy, sz, 1.0])


def rotation_x(angle):
    """Rotation by `angle` radians about +x (right-handed)."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1]], dtype=float)


def rotation_y(angle):
    """Rotation by `angle` radians about +y, the vertical axis (a turntable)."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0, s, 0], [0, 1, 0, 0], [-s, 0, c, 0], [0, 0, 0, 1]], dtype=float)


def rotation_z(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]], dtype=float)


def world_values(matrix):
    """The 16 column-major values of a 4x4 matrix (numpy array or nested rows). A flat sequence of 16 is taken as
    already column-major (glTF order) and returned as floats. ValueError for any other shape or a non-finite value."""
    m = np.asarray(matrix, dtype=float)
    if m.shape == (4, 4):
        values = m.flatten(order="F")
    elif m.shape == (16,):
        values = m
    else:
        raise ValueError(f"a world matrix is 4x4 (or 16 column-major values), got shape {m.shape}")
    if not np.all(np.isfinite(values)):
        raise ValueError("a world matrix must hold finite values")
    return [float(v) for v in values]
