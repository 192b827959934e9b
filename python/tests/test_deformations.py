"""The paper examples of `make`, lattices and free-form deformation from Python, against the
command line on the same input (docs/python.md), and the identities that tie them together."""
import json

import numpy as np
import pytest

import volspline


def obj_vertices(path):
    """The vertex positions of an OBJ file (the writer prints 17 significant digits: exact)."""
    return np.array([[float(x) for x in line.split()[1:4]] for line in path.read_text().splitlines() if line.startswith("v ")])


def assert_same_spline(a, b):
    assert a.degrees == b.degrees
    for ka, kb in zip(a.knots, b.knots):
        np.testing.assert_allclose(ka, kb, rtol=0, atol=1e-12)
    scale = max(1.0, np.abs(b.control_points).max())
    np.testing.assert_allclose(a.control_points, b.control_points, rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(a.weights, b.weights, rtol=0, atol=1e-12)


@pytest.mark.parametrize("kind, args, make", [
    ("swept-patch", [], volspline.swept_patch),
    ("twisted-loft", [], volspline.twisted_loft),
    ("curved-loft", [], volspline.curved_loft),
    ("hyperboloid", ["--throat-radius", "1.5", "--half-height", "0.75", "--center", "1,-2,0.5"],
     lambda: volspline.hyperboloid(1.5, 0.75, [1, -2, 0.5])),
])
def test_paper_examples_equal_the_command_lines(tmp_path, cli, kind, args, make):
    code, _, err = cli("make", kind, *args, "-o", tmp_path / "made.json")
    assert code == 0, err
    (made,) = volspline.read(tmp_path / "made.json")
    assert_same_spline(make(), made.spline)


def test_the_hyperboloid_lies_on_its_quadric():
    a, h = 1.5, 0.75
    center = np.array([1.0, -2.0, 0.5])
    solid = volspline.hyperboloid(a, h, center)
    assert (solid.weights == 0).any()  # points at infinity (Lasser Fig. 3)
    t = np.random.default_rng(4).random((200, 3))
    # The outer face is the hyperboloid x^2 + y^2 - z^2 = a^2: the face of the largest |x^2 + y^2 - z^2|.
    values = []
    for face in range(3):
        for side in (0.0, 1.0):
            s = t.copy()
            s[:, face] = side
            x = solid.evaluate(s) - center
            values.append(x[:, 0] ** 2 + x[:, 1] ** 2 - x[:, 2] ** 2)
    assert min(np.abs(v - a * a).max() for v in values) < 1e-12
    assert np.abs(solid.evaluate(t)[:, 2] - center[2]).max() <= h + 1e-12


@pytest.fixture
def ball_mesh():
    return volspline.boundary(volspline.ball(1.0, [0.5, 0.0, 0.25]), face_resolution=8)


@pytest.fixture
def lattice_file(tmp_path, cli, ball_mesh):
    volspline.write_mesh(tmp_path / "ball.obj", ball_mesh)
    code, _, err = cli("lattice", tmp_path / "ball.obj", "--degree", "2,3,1", "--divisions", "2,1,3", "--margin", "0.1",
                       "--axes", "1,1,0,-1,1,0,0,0.5,1", "-o", tmp_path / "lattice.json")
    assert code == 0, err
    return tmp_path / "lattice.json"


def test_lattice_equals_the_command_line_and_is_the_identity(tmp_path, ball_mesh, lattice_file):
    axes = np.array([[1.0, -1.0, 0.0], [1.0, 1.0, 0.5], [0.0, 0.0, 1.0]])  # the columns are U, V, W
    lattice = volspline.lattice(ball_mesh, (2, 3, 1), (2, 1, 3), 0.1, axes)
    (written,) = volspline.read(lattice_file)
    assert_same_spline(lattice.volume, written.spline)
    read_back = volspline.lattice_from(lattice_file)
    np.testing.assert_allclose(read_back.origin, lattice.origin, rtol=0, atol=1e-12)
    np.testing.assert_allclose(read_back.axes, lattice.axes, rtol=0, atol=1e-12)
    # The box's edges are the given directions, scaled.
    for k in range(3):
        assert abs(abs(np.dot(lattice.axes[:, k], axes[:, k])) - np.linalg.norm(lattice.axes[:, k]) * np.linalg.norm(axes[:, k])) < 1e-9
    # An undeformed lattice is the identity map, inside the box and outside.
    points = np.vstack([ball_mesh["vertices"], [[10.0, -3.0, 2.0]]])
    np.testing.assert_allclose(volspline.ffd(lattice, points), points, rtol=0, atol=1e-12)
    # Written through volspline.write, it is the same lattice file for the command line.
    volspline.write(tmp_path / "again.json", lattice.to_objects())
    assert_same_spline(volspline.lattice_from(tmp_path / "again.json").volume, lattice.volume)


def bend(lattice_file, out):
    """The lattice file with three control points moved."""
    data = json.loads(lattice_file.read_text())
    points = data["objects"][0]["control_points"]
    for i, shift in [(3, [0.3, -0.1, 0.2]), (17, [0.0, 0.4, -0.25]), (len(points) - 2, [-0.2, 0.0, 0.35])]:
        points[i] = [c + d for c, d in zip(points[i], shift)]
    out.write_text(json.dumps(data))
    return out


def test_ffd_of_a_mesh_and_of_points_equals_the_command_line(tmp_path, cli, ball_mesh, lattice_file):
    bent_file = bend(lattice_file, tmp_path / "bent.json")
    bent = volspline.lattice_from(bent_file)
    code, _, err = cli("ffd", bent_file, tmp_path / "ball.obj", "-o", tmp_path / "deformed.obj")
    assert code == 0, err
    deformed = volspline.ffd(bent, ball_mesh)
    np.testing.assert_allclose(deformed["vertices"], obj_vertices(tmp_path / "deformed.obj"), rtol=0, atol=1e-12)
    np.testing.assert_array_equal(deformed["triangles"], ball_mesh["triangles"])
    # Points and the mesh's vertices move alike; a path to the lattice file works as the lattice.
    np.testing.assert_array_equal(volspline.ffd(bent_file, ball_mesh["vertices"]), deformed["vertices"])
    assert not np.allclose(deformed["vertices"], ball_mesh["vertices"], atol=1e-3)  # it did bend


def test_ffd_of_curves_and_surfaces_is_exact_and_equals_the_command_line(tmp_path, cli, lattice_file):
    # Exact composition needs one polynomial piece of the lattice map: a single-cell lattice.
    code, _, err = cli("lattice", tmp_path / "ball.obj", "--degree", "2,1,2", "-o", tmp_path / "bezier.json")
    assert code == 0, err
    bent_file = bend(tmp_path / "bezier.json", tmp_path / "bent.json")
    bent = volspline.lattice_from(bent_file)
    curve = volspline.Curve([2], [np.array([0, 0, 0, 0.5, 1, 1, 1.0])],
                            np.array([[0.0, -0.3, 0.1], [0.5, 0.2, 0.3], [0.8, 0.1, 0.6], [1.0, -0.2, 0.4]]))
    surface = volspline.Surface([1, 2], [np.array([0, 0, 1, 1.0]), np.array([0, 0, 0, 1, 1, 1.0])],
                                np.array([[0.1, -0.2, 0.2], [0.9, -0.2, 0.3], [0.2, 0.0, 0.5], [0.8, 0.1, 0.4],
                                          [0.0, 0.2, 0.3], [1.0, 0.3, 0.35]]))
    volspline.write(tmp_path / "shapes.json", [curve, surface])
    code, _, err = cli("ffd", bent_file, tmp_path / "shapes.json", "-o", tmp_path / "deformed.json")
    assert code == 0, err
    by_cli = [o.spline for o in volspline.read(tmp_path / "deformed.json")]
    by_python = [o.spline for o in volspline.ffd(bent, tmp_path / "shapes.json")]
    composed = [volspline.ffd(bent, curve), volspline.ffd(bent, surface)]
    for a, b, c in zip(by_python, by_cli, composed):
        assert_same_spline(a, b)
        assert_same_spline(c, b)
    # Composition is exact: the deformed curve at t is the deformed point curve(t).
    t = np.linspace(0, 1, 41)[:, None]
    np.testing.assert_allclose(composed[0].evaluate(t), volspline.ffd(bent, curve.evaluate(t)), rtol=0, atol=1e-12)
    st = np.random.default_rng(2).random((100, 2))
    np.testing.assert_allclose(composed[1].evaluate(st), volspline.ffd(bent, surface.evaluate(st)), rtol=0, atol=1e-12)


def test_wrong_input_is_refused_with_a_clear_error(tmp_path, lattice_file):
    lattice = volspline.lattice_from(lattice_file)
    with pytest.raises(volspline.InvalidInput, match=r"points: expected an array of shape \(N, 3\)"):
        volspline.ffd(lattice, np.zeros((4, 2)))
    with pytest.raises(volspline.InvalidInput, match="around: expected an array of shape"):
        volspline.lattice(np.zeros((4, 2)), (1, 1, 1))
    volspline.write(tmp_path / "ball.json", [volspline.ball(1.0)])
    with pytest.raises(volspline.InvalidInput, match="ball.json"):
        volspline.lattice_from(tmp_path / "ball.json")
    with pytest.raises(volspline.InvalidInput, match=r"domain must be \[0, 1\]"):
        lattice.with_volume(volspline.Volume([1, 1, 1], [np.array([0, 0, 2, 2.0])] * 3, np.zeros((8, 3))))
    # The segmented lattice is a different polynomial in each cell: exact composition is refused.
    curve = volspline.Curve([1], [np.array([0, 0, 1, 1.0])], lattice.volume.evaluate(np.array([[0.1, 0.5, 0.5], [0.9, 0.5, 0.5]])))
    with pytest.raises(volspline.InvalidInput, match="crosses the knot planes"):
        volspline.ffd(lattice, curve)
