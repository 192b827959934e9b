"""A tour of volspline from Python: build, check, look at and export solids (docs/python.md).

Run from the repository after building (`make build`):

    PYTHONPATH=build/python /usr/bin/python3 examples/python/tour.py OUT_DIR

Each step is a cell of a notebook: it prints what it found and writes a picture or a file into
OUT_DIR (default out/python-tour).
"""
import pathlib
import sys

import numpy as np

import volspline

out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "out/python-tour")
out.mkdir(parents=True, exist_ok=True)

# %% 1. An exact rational solid: the ball of radius 2. Its sphere (u = 1) is exact.
ball = volspline.ball(2.0)
u = np.random.default_rng(0).random((1000, 3))
u[:, 0] = 1.0
print("ball: largest |(|x| - 2)| on the sphere:", np.abs(np.linalg.norm(ball.evaluate(u), axis=1) - 2).max())

# %% 2. A certified Jacobian check: is the map regular everywhere, and which way does it turn?
# The ball's map is singular at its centre (u = 0), so it is certified invalid with a witness;
# a thick hollow cylinder is regular.
check = volspline.check_jacobian(ball)
print("ball Jacobian:", check["verdict"], "witness (u, v, w) =", check["witness"])
tube = volspline.cylinder(2.0, 1.0, inner=1.0)
check = volspline.check_jacobian(tube)
print("hollow cylinder Jacobian:", check["verdict"], "orientation", check["orientation"],
      "bounds", (check["lower"], check["upper"]))

# %% 3. Looking inside (Lasser §IV): three slices coloured by the Jacobian, as `volspline view`.
picture = volspline.view(ball, slices=[("x", 3)], color="jacobian", size=(640, 480), png=out / "ball-slices.png")
print("slices:", len(picture["mesh"]["triangles"]), "triangles, Jacobian range", picture["range"])

# %% 4. A folded solid and its true boundary (Joy-Duchaineau): faces plus the surface J = 0.
folded = volspline.half_cylinder_sweep()
boundary = volspline.boundary(folded, progress=lambda phase, fraction: None)
print("half-cylinder sweep boundary parts:", boundary["part_names"])
volspline.write_png(out / "boundary.png", volspline.render(boundary, size=(640, 480)))
volspline.write_mesh(out / "boundary.ply", boundary)

# %% 5. A swept solid (Conkey-Joy): a box moved along a segment; its envelope is the hull of the
# two end boxes, whose volume is known exactly.
path = volspline.Curve([1], [np.array([0.0, 0.0, 1.0, 1.0])], np.array([[0.0, 0.0, 0.0], [3.0, -1.0, 2.0]]))
swept = volspline.swept_solid(volspline.box(np.array([1.0, 2.0, 0.5])), path)
envelope = volspline.sweep_envelope(swept)
exact = 1 * 2 * 0.5 + 3 * 2 * 0.5 + 1 * 1 * 0.5 + 2 * 1 * 2  # abc + |dx| bc + |dy| ac + |dz| ab
print("envelope: closed", envelope["stats"]["closed"], "volume", envelope["stats"]["volume"], "exact", exact)
volspline.write_png(out / "envelope.png", volspline.render(envelope, size=(640, 480)))

# %% 6. A heterogeneous solid (Hua-He-Qin): a simplex spline over a Delaunay domain with a
# density attribute, its X-ray and an isosurface.
points = np.random.default_rng(1).random((150, 3)) * 2 - 1
solid = volspline.simplex_spline(2, points=points)
solid.assign_attribute("density", lambda x, y, z: np.exp(-4 * (x * x + y * y + z * z)))
xray = volspline.xray(solid, "density", size=(192, 192))
volspline.write_png(out / "xray.png", xray["image"])
iso = volspline.simplex_isosurface(solid, "density", 0.5, edge=0.15)  # sampling edges of at most 0.15
print("density isosurface:", len(iso["triangles"]), "triangles")
volspline.write_png(out / "isosurface.png", volspline.render(iso, size=(480, 480)))

# %% 7. Export: model files for volspline and G+Smo, meshes to meshio and VTK objects.
volspline.write(out / "ball.json", [ball])
volspline.write(out / "ball.xml", [ball])
grid = volspline.to_vtk(ball)
print("VTK grid of the ball:", grid.GetNumberOfCells(), "rational Bezier cells")
volspline.to_meshio(boundary).write(out / "boundary.vtu")
print("wrote", sorted(p.name for p in out.iterdir()))
