"""check_jacobian and boundary against analytic answers and the CLI."""
import json

import numpy as np

import volspline


def test_box_jacobian_is_certified_constant(tmp_path, cli):
    box = volspline.box(np.array([1.0, 2.0, 3.0]))
    result = volspline.check_jacobian(box)
    assert result["verdict"] == "valid" and result["orientation"] == 1
    assert abs(result["lower"] - 6.0) < 1e-9 and abs(result["upper"] - 6.0) < 1e-9
    volspline.write(tmp_path / "box.json", [box])
    code, out, err = cli("jacobian", tmp_path / "box.json", "--json")
    assert code == 0, err
    (cli_result,) = json.loads(out)["objects"]
    assert cli_result["verdict"] == result["verdict"]
    assert cli_result["lower"] == result["lower"] and cli_result["upper"] == result["upper"]


def test_folded_volume_is_invalid_with_a_witness():
    # x = u, y = v^3/3 - s v, z = w folds where J = v^2 - s changes sign (s = 0.25: v = 0.5).
    k3 = np.array([0, 0, 0, 0, 1, 1, 1, 1.0])
    k1 = np.array([0, 0, 1, 1.0])
    # y(v) = v^3/3 - v/4 in Bernstein form on [0, 1]: coefficients 0, -1/12, -1/6, 1/12.
    y = [0.0, -1 / 12, -1 / 6, 1 / 12]
    cp = np.zeros((2, 4, 2, 3))
    for i in range(2):
        for j in range(4):
            for k in range(2):
                cp[i, j, k] = [i, y[j], k]
    vol = volspline.Volume([1, 3, 1], [k1, k3, k1], cp)
    result = volspline.check_jacobian(vol)
    assert result["verdict"] == "invalid"

    def jacobian(point):
        d = vol.evaluate(np.array(point), order=1)
        return np.linalg.det(np.stack([d[1], d[2], d[3]], axis=1))

    # J = v^2 - 1/4 (x_u = z_w = 1): the witness and the reference point lie on opposite sides of v = 1/2.
    assert jacobian(result["witness"]) * jacobian(result["reference_point"]) <= 0
    assert abs(jacobian(result["witness"]) - (result["witness"][1] ** 2 - 0.25)) < 1e-12


def test_box_boundary_lies_on_the_box():
    box = volspline.box(np.array([1.0, 2.0, 3.0]))
    b = volspline.boundary(box, face_resolution=4)
    v, tri, parts = b["vertices"], b["triangles"], b["parts"]
    assert v.shape[1] == 3 and tri.shape[1] == 3 and parts.shape == (tri.shape[0],)
    assert tri.min() >= 0 and tri.max() < len(v)
    half = np.array([0.5, 1.0, 1.5])
    on_face = np.isclose(np.abs(v), half, atol=1e-12).any(axis=1)
    assert on_face.all()
    assert len(set(parts.tolist())) == 6 and all(isinstance(n, str) for n in b["part_names"].values())
    # Each vertex's (u, v, w) maps to the vertex.
    np.testing.assert_allclose(box.evaluate(b["parameters"]), v, atol=1e-12)
