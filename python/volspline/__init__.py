"""volspline: free-form trivariate spline solids.

Exact tensor-product B-spline curves, surfaces, volumes and 4-variate solids (polynomial and
rational), the constructions of ``volspline make``, model files in every format, certified
Jacobian checks and solid boundaries, pictures of the inside of solids, box-spline blends, swept
solids and their envelopes, free-form deformation, trivariate simplex spline volumes with material attributes (fitting,
X-rays, isosurfaces). numpy arrays in and out; meshes to meshio and VTK. See docs/python.md.

    >>> import volspline, numpy as np
    >>> ball = volspline.ball(2.0)
    >>> ball.evaluate(np.array([[1.0, 0.5, 0.25]]))   # a point on the sphere
"""
import types as _types

from ._volspline import (  # noqa: F401
    Curve,
    Error,
    Hypervolume,
    InvalidInput,
    IoError,
    Lattice,
    ModelObject,
    NotConverged,
    SimplexSplineVolume,
    Surface,
    SweptSolid,
    Volume,
    __version__,
    ball,
    blend,
    boundary,
    box,
    check_jacobian,
    cone,
    curved_loft,
    cylinder,
    extrude,
    ffd,
    fit,
    half_cylinder_sweep,
    half_torus,
    hyperboloid,
    lattice,
    lattice_from,
    loft,
    paper_example_patch,
    read,
    render,
    revolve,
    ruled,
    simplex_boundary,
    simplex_isosurface,
    simplex_slice,
    simplex_spline,
    sweep,
    sweep_envelope,
    swept_patch,
    swept_solid,
    torus,
    translation_volume,
    twisted_loft,
    view,
    vtu_text,
    write,
    write_mesh,
    write_png,
    xray,
)
from .interop import to_meshio, to_vtk  # noqa: F401

__all__ = [n for n, v in globals().items() if not n.startswith("_") and not isinstance(v, _types.ModuleType)]
__all__.append("__version__")
