"""volspline: free-form trivariate spline solids.

Exact tensor-product B-spline curves, surfaces, volumes and 4-variate solids (polynomial and
rational), the constructions of ``volspline make``, model files in every format, certified
Jacobian checks and solid boundaries. numpy arrays in and out; see docs/python.md.

    >>> import volspline, numpy as np
    >>> ball = volspline.ball(2.0)
    >>> ball.evaluate(np.array([[1.0, 0.5, 0.25]]))   # a point on the sphere
"""
from ._volspline import (  # noqa: F401
    Curve,
    Error,
    Hypervolume,
    InvalidInput,
    IoError,
    ModelObject,
    NotConverged,
    Surface,
    Volume,
    __version__,
    ball,
    boundary,
    box,
    check_jacobian,
    cone,
    cylinder,
    extrude,
    half_cylinder_sweep,
    half_torus,
    loft,
    read,
    revolve,
    ruled,
    sweep,
    torus,
    translation_volume,
    write,
)

__all__ = [name for name in dir() if not name.startswith("_")] + ["__version__"]
