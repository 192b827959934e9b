"""Meshes and models to the tools users already have: meshio and VTK (docs/python.md).

Both import their library only when called, so ``import volspline`` needs neither.
"""
import numpy as np

from . import _volspline


def _is_mesh(obj):
    return isinstance(obj, dict) and "vertices" in obj and "triangles" in obj


def to_meshio(mesh):
    """A ``meshio.Mesh`` of a mesh dict (as boundary, blend, view, sweep_envelope return): the
    triangles, the part number per triangle as cell data ``part`` and each vertex's (u, v, w) as
    point data ``parameters`` (plus ``t`` and ``patch`` for swept envelopes, ``values`` for slices)."""
    import meshio

    if not _is_mesh(mesh):
        raise _volspline.InvalidInput("mesh: expected a dict with 'vertices' and 'triangles' (as volspline.boundary returns)")
    point_data = {"parameters": np.asarray(mesh.get("parameters", np.zeros_like(mesh["vertices"])))}
    for key, name in (("times", "t"), ("patches", "patch"), ("values", "values"), ("scalars", "scalars")):
        value = mesh.get(key)
        if value is not None and len(value) == len(mesh["vertices"]):
            point_data[name] = np.asarray(value)
    cell_data = {}
    if "parts" in mesh:
        cell_data["part"] = [np.asarray(mesh["parts"], dtype=np.int32)]
    return meshio.Mesh(
        np.asarray(mesh["vertices"], dtype=float),
        [("triangle", np.asarray(mesh["triangles"], dtype=np.int64))],
        point_data=point_data,
        cell_data=cell_data,
    )


def _polydata(mesh):
    import vtk
    from vtk.util import numpy_support

    vertices = np.ascontiguousarray(mesh["vertices"], dtype=float)
    triangles = np.asarray(mesh["triangles"], dtype=np.int64)
    points = vtk.vtkPoints()
    points.SetData(numpy_support.numpy_to_vtk(vertices, deep=True))
    connectivity = np.hstack([np.full((len(triangles), 1), 3, dtype=np.int64), triangles]).ravel()
    cells = vtk.vtkCellArray()
    cells.SetCells(len(triangles), numpy_support.numpy_to_vtkIdTypeArray(connectivity, deep=True))
    poly = vtk.vtkPolyData()
    poly.SetPoints(points)
    poly.SetPolys(cells)
    if "parts" in mesh:
        part = numpy_support.numpy_to_vtk(np.asarray(mesh["parts"], dtype=np.int32), deep=True)
        part.SetName("part")
        poly.GetCellData().AddArray(part)
    if "parameters" in mesh:
        parameters = numpy_support.numpy_to_vtk(np.ascontiguousarray(mesh["parameters"], dtype=float), deep=True)
        parameters.SetName("parameters")
        poly.GetPointData().AddArray(parameters)
    return poly


def to_vtk(obj):
    """A VTK object: for a mesh dict a ``vtkPolyData`` (cell data ``part``, point data
    ``parameters``); for a model (a path, a Volume, a SimplexSplineVolume, or a list of objects)
    the ``vtkUnstructuredGrid`` that ``volspline convert -o OUT.vtu`` writes: rational Bézier
    cells of the volumes' own degrees (Lagrange tetrahedra for a simplex spline volume), read back
    by VTK's own XML reader from memory."""
    import vtk

    if _is_mesh(obj):
        return _polydata(obj)
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.ReadFromInputStringOn()
    reader.SetInputString(_volspline.vtu_text(obj))
    reader.Update()
    grid = vtk.vtkUnstructuredGrid()
    grid.DeepCopy(reader.GetOutput())
    return grid
