"""view, render, blend, write_mesh and the conversions to meshio and VTK, against the CLI and
analytic answers."""
import json
import math

import numpy as np
import pytest

import volspline


def read_png(path):
    vtk = pytest.importorskip("vtk")
    from vtk.util import numpy_support

    reader = vtk.vtkPNGReader()
    reader.SetFileName(str(path))
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    pixels = numpy_support.vtk_to_numpy(image.GetPointData().GetScalars())
    # VTK's rows run bottom to top.
    return pixels.reshape(height, width, -1)[::-1]


def test_view_gives_the_cli_picture_and_mesh(tmp_path, cli):
    ball = volspline.ball(1.5)
    volspline.write(tmp_path / "ball.json", [ball])
    result = volspline.view(tmp_path / "ball.json", slices=[("x", 3)], color="jacobian", size=(240, 180),
                            png=tmp_path / "py.png")
    code, _, err = cli("view", tmp_path / "ball.json", "-o", tmp_path / "cli.png", "--slices", "x:3", "--color",
                       "jacobian", "--size", "240,180", "--mesh", tmp_path / "cli.ply")
    assert code == 0, err
    image = result["image"]
    assert image.shape == (180, 240, 4) and image.dtype == np.uint8
    assert np.array_equal(read_png(tmp_path / "cli.png"), image)
    assert np.array_equal(read_png(tmp_path / "py.png"), image)
    mesh = result["mesh"]
    # Every slice vertex lies in its plane x = -0.75, 0, 0.75 (three planes evenly inside the box
    # [-1.5, 1.5]) and inside the ball.
    x = mesh["vertices"][:, 0]
    planes = np.array([-0.75, 0.0, 0.75])
    assert np.min(np.abs(x[:, None] - planes[None, :]), axis=1).max() < 1e-9
    assert np.linalg.norm(mesh["vertices"], axis=1).max() < 1.5 + 1e-9
    assert len(result["scalars"]) == len(mesh["vertices"])
    assert len(result["planes"]) == 3


def test_view_of_a_volume_with_attributes_and_bad_requests(tmp_path):
    box = volspline.box(np.array([2.0, 1.0, 1.0]))
    # An attribute equal to x at the corners: trilinear, so it is x everywhere.
    # Attribute values come in the library's order, u fastest (docs/python.md, "Arrays").
    cp = box.control_points.transpose(2, 1, 0, 3).reshape(-1, 3)
    obj = volspline.ModelObject(box, "box", {"temperature": list(cp[:, 0])})
    result = volspline.view([obj], planes=[((0.0, 0.0, 1.0), 0.1)], color="temperature", size=(120, 90))
    vertices = result["mesh"]["vertices"]
    assert np.allclose(result["scalars"], vertices[:, 0], atol=1e-12)
    assert np.allclose(vertices[:, 2], 0.1, atol=1e-12)
    with pytest.raises(volspline.InvalidInput, match="slices"):
        volspline.view(box, slices=[("q", 3)])
    with pytest.raises(volspline.InvalidInput, match="attribute|pressure"):
        volspline.view([obj], faces=True, color="pressure")
    with pytest.raises(volspline.InvalidInput, match="range"):
        volspline.view(box, range=(1.0, 0.0))


def test_render_shows_the_mesh_and_colours_by_scalars():
    mesh = volspline.boundary(volspline.ball(1.0))
    plain = volspline.render(mesh, size=(160, 120))
    assert plain.shape == (120, 160, 4)
    background = plain[0, 0, :3].astype(int)
    covered = np.any(np.abs(plain[:, :, :3].astype(int) - background) > 30, axis=2).mean()
    assert 0.2 < covered < 0.95
    coloured = volspline.render(mesh, size=(160, 120), scalars=mesh["vertices"][:, 2], title="z")
    assert not np.array_equal(plain, coloured)
    with pytest.raises(volspline.InvalidInput, match="triangles"):
        volspline.render({"vertices": mesh["vertices"], "triangles": np.array([[0, 1, 10**9]])})
    with pytest.raises(volspline.InvalidInput, match="vertices"):
        volspline.render({"triangles": mesh["triangles"]})


def test_blend_of_one_sphere_matches_the_cli_and_lies_on_the_sphere(tmp_path, cli):
    scene = {"volspline_scene": 1, "spacing": 0.1, "box": {"min": [-1, -1, -1], "max": [1, 1, 1]},
             "root": {"sphere": {"center": [0, 0, 0], "radius": 0.6}}}
    path = tmp_path / "sphere.json"
    path.write_text(json.dumps(scene))
    from_dict = volspline.blend(scene, method="exact", project=True)
    from_file = volspline.blend(path, method="exact", project=True)
    assert np.array_equal(from_dict["vertices"], from_file["vertices"])
    radii = np.linalg.norm(from_dict["vertices"], axis=1)
    assert from_dict["stats"]["closed"]
    assert abs(radii - 0.6).max() <= from_dict["stats"]["max_distance"] + 1e-15
    assert from_dict["stats"]["max_distance"] < 1e-3
    code, _, err = cli("blend", path, "-o", tmp_path / "cli.ply", "--method", "exact", "--project", "--stats",
                       tmp_path / "stats.json")
    assert code == 0, err
    stats = json.loads((tmp_path / "stats.json").read_text())
    assert stats["triangles"] == len(from_dict["triangles"])
    assert stats["max_distance"] == from_dict["stats"]["max_distance"]
    assert set(np.unique(from_dict["parts"])) == {11}
    with pytest.raises(volspline.InvalidInput, match="scene"):
        volspline.blend({"volspline_scene": 1, "root": {"sphere": {"radius": -1}}})


def test_blend_shows_the_ingredients_as_the_cli_does(tmp_path, cli):
    """show='union' / 'primitives' / 'spline' give the meshes `volspline blend --show` writes."""
    scene = {"volspline_scene": 1, "spacing": 0.2, "box": {"min": [-0.6, -0.6, -0.6], "max": [0.6, 0.6, 0.6]},
             "domain": {"min": [-1.6, -1.2, -1.2], "max": [1.6, 1.2, 1.2]},
             "root": {"blend": {"radius": 0.2, "of": [{"sphere": {"center": [-0.5, 0, 0], "radius": 0.8}},
                                                            {"sphere": {"center": [0.5, 0, 0], "radius": 0.8}}]}}}
    path = tmp_path / "spheres.json"
    path.write_text(json.dumps(scene))
    blend = volspline.blend(path)
    for show in ("union", "primitives", "spline"):
        mine = volspline.blend(path, show=show, spacing=0.05 if show != "spline" else 0.0)
        args = ["--show", show] + (["--spacing", "0.05"] if show != "spline" else [])
        code, _, err = cli("blend", path, "-o", tmp_path / f"{show}.ply", *args, "--stats", tmp_path / f"{show}.json")
        assert code == 0, err
        theirs = json.loads((tmp_path / f"{show}.json").read_text())
        assert theirs["show"] == mine["stats"]["show"] == show
        if show == "spline":
            assert len(mine["triangles"]) == theirs["spline_triangles"] > 100
        else:
            assert len(mine["triangles"]) == theirs["triangles"] > 100
            assert mine["stats"]["grid_spacing"] == theirs["grid_spacing"] == 0.05
    spline = volspline.blend(path, show="spline")
    assert set(np.unique(spline["parts"])) == {11}
    assert len(spline["triangles"]) == int((blend["parts"] == 11).sum())
    # On the surface of min(|x - a| - r, |x - b| - r) to the grid's accuracy.
    union = volspline.blend(path, show="union", spacing=0.05)
    x = union["vertices"]
    f = np.minimum(np.linalg.norm(x - [-0.5, 0, 0], axis=1), np.linalg.norm(x - [0.5, 0, 0], axis=1)) - 0.8
    assert abs(f).max() < 2e-3
    assert union["stats"]["closed"]
    with pytest.raises(volspline.InvalidInput, match="show"):
        volspline.blend(path, show="everything")
    with pytest.raises(volspline.InvalidInput, match="spacing"):
        volspline.blend(path, spacing=0.1)


def test_write_mesh_and_meshio_and_vtk_agree(tmp_path):
    meshio = pytest.importorskip("meshio")
    vtk = pytest.importorskip("vtk")
    mesh = volspline.boundary(volspline.box(np.array([1.0, 2.0, 3.0])))
    volspline.write_mesh(tmp_path / "box.ply", mesh)
    m = volspline.to_meshio(mesh)
    assert np.array_equal(m.points, mesh["vertices"])
    assert np.array_equal(m.cells_dict["triangle"], mesh["triangles"])
    assert np.array_equal(m.cell_data["part"][0], mesh["parts"])
    meshio.write(tmp_path / "box.vtu", m)
    back = meshio.read(tmp_path / "box.vtu")
    assert np.allclose(back.points, mesh["vertices"])
    poly = volspline.to_vtk(mesh)
    assert poly.GetNumberOfPoints() == len(mesh["vertices"]) and poly.GetNumberOfCells() == len(mesh["triangles"])
    mass = vtk.vtkMassProperties()
    triangles = vtk.vtkTriangleFilter()
    triangles.SetInputData(poly)
    mass.SetInputConnection(triangles.GetOutputPort())
    mass.Update()
    assert abs(mass.GetVolume() - 6.0) < 1e-9


def test_to_vtk_of_a_volume_is_bezier_cells_that_vtk_evaluates_exactly():
    vtk = pytest.importorskip("vtk")
    ball = volspline.ball(2.0)
    grid = volspline.to_vtk(ball)
    # One rational Bezier cell per knot span: 1 x 2 x 4 for the ball's knots.
    spans = [len(np.unique(k)) - 1 for k in ball.knots]
    assert grid.GetNumberOfCells() == math.prod(spans)
    assert {grid.GetCellType(i) for i in range(grid.GetNumberOfCells())} == {vtk.VTK_BEZIER_HEXAHEDRON}
    # VTK's own evaluation of cell 0 (the first span in each direction, parametric coordinates
    # r, s, t along u, v, w) equals ours at the same parameters.
    cell = grid.GetCell(0)
    weights = [0.0] * cell.GetNumberOfPoints()
    ends = [np.unique(k)[1] for k in ball.knots]
    rng = np.random.default_rng(3)
    for rst in rng.random((20, 3)):
        x = [0.0, 0.0, 0.0]
        cell.EvaluateLocation(vtk.reference(0), list(rst), x, weights)
        ours = ball.evaluate(rst * np.array(ends))
        assert np.linalg.norm(np.array(x) - ours) < 1e-12
