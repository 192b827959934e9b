"""The spline bindings against analytic answers, the library's own identities and the CLI."""
import json
import resource

import numpy as np
import pytest

import volspline


def trilinear_volume():
    # x = u + 0.1 v w, y = 2 v, z = 3 w + 0.2 u^2: degree (2, 1, 1) on a clamped knot vector.
    ku = np.array([0, 0, 0, 1, 1, 1.0])
    kv = kw = np.array([0, 0, 1, 1.0])
    cp = np.zeros((3, 2, 2, 3))
    greville_u = [0.0, 0.5, 1.0]
    for i, gu in enumerate(greville_u):
        for j in range(2):
            for k in range(2):
                # The control points of u (Greville abscissae) and of u^2 (0, 0, 1).
                cp[i, j, k] = [gu + 0.1 * j * k, 2.0 * j, 3.0 * k + 0.2 * [0, 0, 1][i]]
    return volspline.Volume([2, 1, 1], [ku, kv, kw], cp)


def exact(t):
    u, v, w = t.T
    return np.stack([u + 0.1 * v * w, 2 * v, 3 * w + 0.2 * u**2], axis=1)


def test_control_points_are_a_view_in_the_given_layout():
    vol = trilinear_volume()
    cp = vol.control_points
    assert cp.shape == (3, 2, 2, 3)
    assert not cp.flags.writeable
    assert cp.base is not None  # a view of the library's storage, not a copy
    assert vol.degrees == [2, 1, 1] and vol.num_control_points == [3, 2, 2] and vol.dimension == 3
    # The flat form (first index fastest) gives the same spline.
    flat = np.ascontiguousarray(cp.transpose(2, 1, 0, 3)).reshape(-1, 3)
    again = volspline.Volume(vol.degrees, vol.knots, flat)
    np.testing.assert_array_equal(again.control_points, cp)


def test_evaluation_reproduces_the_polynomial_exactly():
    vol = trilinear_volume()
    t = np.random.default_rng(1).random((500, 3))
    np.testing.assert_allclose(vol.evaluate(t), exact(t), atol=1e-14)
    assert vol.evaluate(t[0]).shape == (3,)


def test_derivatives_match_the_analytic_ones():
    vol = trilinear_volume()
    t = np.random.default_rng(2).random((50, 3))
    d = vol.evaluate(t, order=1)
    assert d.shape == (50, 4, 3)
    assert volspline.Volume.multi_indices(1) == [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
    u, v, w = t.T
    np.testing.assert_allclose(d[:, 1], np.stack([np.ones(50), 0 * u, 0.4 * u], 1), atol=1e-13)
    np.testing.assert_allclose(d[:, 2], np.stack([0.1 * w, 2 + 0 * u, 0 * u], 1), atol=1e-13)
    np.testing.assert_allclose(d[:, 3], np.stack([0.1 * v, 0 * u, 3 + 0 * u], 1), atol=1e-13)


def test_grid_evaluation_equals_pointwise_evaluation():
    vol = volspline.ball(1.5)
    u, v, w = np.linspace(0, 1, 4), np.linspace(0, 1, 5), np.linspace(0, 1, 6)
    grid = vol.evaluate_grid([u, v, w])
    assert grid.shape == (4, 5, 6, 3)
    pts = np.stack(np.meshgrid(u, v, w, indexing="ij"), -1).reshape(-1, 3)
    np.testing.assert_allclose(grid.reshape(-1, 3), vol.evaluate(pts), atol=1e-14)
    d = vol.evaluate_grid([u, v, w], order=1)
    assert d.shape == (4, 4, 5, 6, 3)
    np.testing.assert_allclose(d[0], grid, atol=1e-14)


def test_exact_ball_lies_on_its_sphere():
    center = np.array([1.0, -2.0, 0.5])
    ball = volspline.ball(2.0, center)
    assert ball.is_rational
    s = np.random.default_rng(3).random((1000, 3))
    s[:, 0] = 1.0
    r = np.linalg.norm(ball.evaluate(s) - center, axis=1)
    np.testing.assert_allclose(r, 2.0, atol=1e-12)


def test_refinement_keeps_the_geometry():
    ball = volspline.ball(1.0)
    t = np.random.default_rng(4).random((200, 3))
    ref = ball.evaluate(t)
    for other in (ball.insert_knot(1, 0.3, 2), ball.elevate_degree(0, 2), ball.refine_knots(2, [0.1, 0.7])):
        np.testing.assert_allclose(other.evaluate(t), ref, atol=1e-13)
    pieces = ball.bezier_pieces()
    assert len(pieces) == 1 * 2 * 4
    left, right = ball.split(0, 0.5)
    np.testing.assert_allclose(left.evaluate(np.array([0.5, 0.3, 0.2])), ball.evaluate(np.array([0.5, 0.3, 0.2])), atol=1e-13)
    assert right.domain[0] == (0.5, 1.0)


def test_wrong_shapes_and_values_are_refused_with_a_clear_error():
    vol = trilinear_volume()
    with pytest.raises(volspline.InvalidInput, match=r"control_points: axis 0 has 2 entries"):
        volspline.Volume([2, 1, 1], vol.knots, np.zeros((2, 2, 2, 3)))
    with pytest.raises(ValueError, match=r"params: expected an array of shape \(N, 3\)"):
        vol.evaluate(np.zeros((4, 2)))
    with pytest.raises(volspline.InvalidInput, match="outside"):
        vol.evaluate(np.array([[2.0, 0.0, 0.0]]))
    with pytest.raises(volspline.InvalidInput, match=r"knots\[0\]"):
        volspline.Volume([2, 1, 1], [np.array([1.0, 0.0]), vol.knots[1], vol.knots[2]], vol.control_points)
    assert issubclass(volspline.InvalidInput, volspline.Error) and issubclass(volspline.IoError, OSError)


def test_models_round_trip_and_the_cli_reads_them(tmp_path, cli):
    ball = volspline.ball(2.0)
    path = tmp_path / "ball.json"
    volspline.write(path, [volspline.ModelObject(ball, name="ball", attributes={"id": list(range(90))})])
    (obj,) = volspline.read(path)
    assert obj.name == "ball" and obj.type == "bspline_volume" and len(obj.attributes["id"]) == 90
    np.testing.assert_array_equal(obj.spline.control_points, ball.control_points)
    np.testing.assert_array_equal(obj.spline.weights, ball.weights)
    code, out, err = cli("eval", path, "--at", "1,0.5,0.25", "--json")
    assert code == 0, err
    np.testing.assert_allclose(json.loads(out)["points"][0], ball.evaluate(np.array([1, 0.5, 0.25])), atol=1e-12)
    # Other formats by extension.
    volspline.write(tmp_path / "ball.xml", [ball])
    np.testing.assert_allclose(volspline.read(tmp_path / "ball.xml")[0].spline.control_points, ball.control_points)


def test_read_errors_name_the_file(tmp_path):
    with pytest.raises(OSError, match="nothere.json"):
        volspline.read(tmp_path / "nothere.json")
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "volspline", "version": 1, "objects": [{"type": "bspline_volume"}]}')
    with pytest.raises(volspline.InvalidInput, match="bad.json"):
        volspline.read(bad)


def test_memory_is_stable_over_many_calls():
    vol = volspline.ball(1.0)
    t = np.random.default_rng(5).random((100, 3))
    for _ in range(1000):
        vol.evaluate(t)
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    for _ in range(10000):
        vol.evaluate(t)
        vol.control_points
    after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    assert after - before < 20000  # kilobytes
