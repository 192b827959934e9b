"""Swept solids, their envelopes and simplex spline volumes from Python, against analytic answers
and the CLI; progress callbacks and the GIL."""
import json
import sys
import threading

import numpy as np
import pytest

import volspline


def segment(a, b):
    return volspline.Curve([1], [np.array([0.0, 0.0, 1.0, 1.0])], np.array([a, b], dtype=float))


def test_swept_solid_is_the_moved_generator():
    box = volspline.box(np.array([1.0, 2.0, 0.5]))
    d = np.array([3.0, -1.0, 2.0])
    solid = volspline.swept_solid(box, segment([0, 0, 0], d))
    assert solid.frame_name == "fixed" and solid.frame_fit_error == 0
    (patch,) = solid.patches()
    p = np.random.default_rng(1).random((50, 4))
    assert np.allclose(patch.evaluate(p), box.evaluate(p[:, :3]) + p[:, 3:4] * d, atol=1e-14)
    # An exact rotation: R(1) turns by 90 degrees about z.
    turning = volspline.swept_solid([box], segment([0, 0, 0], [0, 0, 1]), ("rotate", (0, 0, 1), 90))
    assert np.allclose(turning.frame_at(1.0), [[0, -1, 0], [1, 0, 0], [0, 0, 1]], atol=1e-15)
    with pytest.raises(volspline.InvalidInput, match="frame"):
        volspline.swept_solid(box, segment([0, 0, 0], d), "twist")


def test_envelope_of_a_translated_box_is_the_hull(tmp_path, cli):
    a, b, c = 1.0, 2.0, 0.5
    d = np.array([3.0, -1.0, 2.0])
    solid = volspline.swept_solid(volspline.box(np.array([a, b, c])), segment([0, 0, 0], d))
    envelope = volspline.sweep_envelope(solid)
    stats = envelope["stats"]
    exact = a * b * c + abs(d[0]) * b * c + abs(d[1]) * a * c + abs(d[2]) * a * b
    assert stats["closed"] and stats["oriented"] and stats["self_intersection_free"]
    assert abs(stats["volume"] - exact) < 1e-9
    assert len(envelope["times"]) == len(envelope["vertices"])
    assert envelope["times"].min() >= 0 and envelope["times"].max() <= 1
    superset = volspline.sweep_envelope(solid, superset=True)
    assert set(np.unique(superset["parts"])) <= {13, 14, 15}
    with pytest.raises(volspline.InvalidInput, match="coarse_cells"):
        volspline.sweep_envelope(solid, coarse_cells=-1)
    with pytest.raises(volspline.InvalidInput, match="adaptive_cells"):
        volspline.sweep_envelope(solid, adaptive_cells=3)
    with pytest.raises(volspline.InvalidInput, match="adaptive_cells"):
        volspline.sweep_envelope(solid, adaptive_cells=64, tolerance=2e-3)
    with pytest.raises(volspline.InvalidInput, match="not both"):
        volspline.sweep_envelope(solid, adaptive_cells=4, coarse_cells=16)
    uniform = volspline.sweep_envelope(solid, adaptive_cells=0)["stats"]
    assert uniform["closed"] and abs(uniform["volume"] - exact) < 1e-9
    with pytest.raises(volspline.InvalidInput, match="refine"):
        volspline.sweep_envelope(solid, coarse_cells=16, refine=0)
    volspline.write(tmp_path / "swept.json", [solid])
    (back,) = volspline.read(tmp_path / "swept.json")
    assert back.type == "swept_solid" and isinstance(back.spline, volspline.SweptSolid)
    code, _, err = cli("sweep-envelope", tmp_path / "swept.json", "-o", tmp_path / "hull.ply", "--stats", tmp_path / "s.json")
    assert code == 0, err
    cli_stats = json.loads((tmp_path / "s.json").read_text())
    assert abs(cli_stats["objects"][0]["volume"] - stats["volume"]) < 1e-12


def cube_points():
    corners = np.array([[i, j, k] for k in (0, 1) for j in (0, 1) for i in (0, 1)], dtype=float)
    return np.vstack([corners, [[0.5, 0.5, 0.5]]])


def test_capsule_is_contoured_and_reports_its_adaptations():
    # A ball along a segment: trimmed by contouring (the arrangement is for polyhedral sweeps),
    # so the contouring's statistics are its own.
    r, length = 1.0, 3.0
    solid = volspline.swept_solid(volspline.ball(r), segment([0, 0, 0], [length, 0, 0]))
    result = volspline.sweep_envelope(solid, tolerance=2e-3)
    stats = result["stats"]
    assert stats["trimmed_by"] == "contouring"
    # Every vertex's (u, v, w, t) maps onto it: here a point of the capsule's surface, at
    # distance r from the segment, within the tolerance (of the control points' diagonal).
    params = np.column_stack([result["parameters"], result["times"]])
    patches = solid.patches() if callable(getattr(solid, "patches", None)) else solid.patches
    assert stats["tags_beyond_tolerance"] == 0
    images = np.array([np.asarray(patches[p].evaluate(q)).ravel()[:3] for p, q in zip(result["patches"][::7], params[::7])])
    assert np.linalg.norm(images - result["vertices"][::7], axis=1).max() <= stats["largest_tag_distance"] + 1e-12
    assert stats["largest_tag_distance"] < 2e-3 * 8
    assert stats["closed"] and stats["oriented"] and stats["self_intersection_free"]
    exact = np.pi * r * r * length + 4 / 3 * np.pi * r ** 3
    assert abs(stats["volume"] - exact) < 2e-3 * exact
    assert stats["grid_adaptation_refused"] is False
    assert stats["grid_adaptations"] >= 0 and stats["refinement_edges_beyond_tolerance"] >= 0


def test_simplex_spline_reproduces_the_identity_and_polynomials(tmp_path, cli):
    volume = volspline.simplex_spline(2, points=cube_points())
    assert volume.degree == 2 and volume.tetrahedra.shape[1] == 4
    x = np.random.default_rng(2).random((200, 3))
    values = volume.evaluate(x, gradients=True)
    assert values["inside"].all()
    assert np.abs(values["geometry"] - x).max() < 1e-12
    assert np.allclose(values["gradients"][:, :3, :], np.eye(3), atol=1e-10)
    outside = volume.evaluate(np.array([2.0, 0.5, 0.5]))
    assert not outside["inside"][0] and not outside["geometry"].any()

    def f(x, y, z):
        return x * y + z - 0.5 * z * z

    # Least squares with the library's small Tikhonov term (docs/simplex-splines.md): a quadratic
    # lies in the spline space, so it comes back to within that term's bias.
    report = volume.assign_attribute("density", f)
    assert report["max_error"] < 1e-8
    values = volume.evaluate(x, gradients=True)
    exact = f(x[:, 0], x[:, 1], x[:, 2])
    assert np.abs(values["attributes"]["density"] - exact).max() < 1e-8
    gradient = np.stack([x[:, 1], x[:, 0], 1 - x[:, 2]], axis=1)
    assert np.abs(values["gradients"][:, 3, :] - gradient).max() < 1e-7
    # The same model through the CLI's eval.
    volspline.write(tmp_path / "s.json", [volume])
    code, out, err = cli("eval", tmp_path / "s.json", "--at", "0.25,0.5,0.75", "--json")
    assert code == 0, err
    cli_point = json.loads(out)["points"][0]
    ours = volume.evaluate(np.array([0.25, 0.5, 0.75]))
    assert np.allclose(cli_point[:3], ours["geometry"][0], atol=1e-15, rtol=0)
    assert abs(cli_point[3] - ours["attributes"]["density"][0]) < 1e-15
    # Isosurface density = 0.3 lies on the level set (the geometry is the identity).
    surface = volspline.simplex_isosurface(volume, "density", 0.3)
    v = surface["vertices"]
    assert len(v) > 0 and np.abs(f(v[:, 0], v[:, 1], v[:, 2]) - 0.3).max() < 1e-8
    plane = volspline.simplex_slice(volume, (0, 0, 1), 0.25, attribute="density")
    assert np.abs(plane["vertices"][:, 2] - 0.25).max() < 1e-12
    pv = plane["vertices"]
    assert np.abs(plane["values"] - f(pv[:, 0], pv[:, 1], pv[:, 2])).max() < 1e-8
    boundary = volspline.simplex_boundary(volume)
    distance_to_faces = np.minimum(np.abs(boundary["vertices"]), np.abs(1 - boundary["vertices"])).min(axis=1)
    assert distance_to_faces.max() < 1e-12


def test_xray_of_the_chord_length_and_the_domain_from_arrays():
    points = cube_points()
    volume = volspline.simplex_spline(1, points=points)
    # The same domain given as arrays.
    again = volspline.simplex_spline(1, points=volume.domain_points, tetrahedra=volume.tetrahedra)
    assert np.array_equal(again.control_vectors, volume.control_vectors)
    picture = volspline.xray(volume, size=(64, 48), view=(0, 0, -1), up=(0, 1, 0))
    integrals = picture["line_integrals"]
    assert integrals.shape == (48, 64) and picture["image"].shape == (48, 64, 4)
    # Parallel rays along z through the unit cube: chord length 1 wherever a ray hits it, else 0.
    hit = integrals > 0.5
    assert hit.sum() > 0.1 * integrals.size
    assert np.abs(integrals[hit] - 1).max() < 1e-12
    assert np.abs(integrals[~hit]).max() < 1e-12
    with pytest.raises(volspline.InvalidInput, match="tetrahedra"):
        volspline.simplex_spline(1, points=points, tetrahedra=np.array([[0, 1, 2, 99]]))
    with pytest.raises(volspline.InvalidInput, match="domain"):
        volspline.simplex_spline(1)


def test_fit_reproduces_a_linear_field_and_reports_table_1():
    rng = np.random.default_rng(4)
    p = rng.random((600, 3))
    data = {"points": p, "attributes": {"temperature": 2 * p[:, 0] - p[:, 1] + 0.5 * p[:, 2]}}
    volume, stats = volspline.fit(data, 1)
    assert stats["data_points"] == 600 and stats["control_points"] > 0
    assert stats["attributes"]["temperature"]["max_abs"] < 1e-9
    assert stats["field_normalised_mean_square"] == stats["attributes"]["temperature"]["normalised_mean_square"]
    inside = p[volume.evaluate(p)["inside"]]
    values = volume.evaluate(inside)["attributes"]["temperature"]
    assert np.abs(values - (2 * inside[:, 0] - inside[:, 1] + 0.5 * inside[:, 2])).max() < 1e-9
    assert stats["primary_knots_layout"] == "farthest" and stats["fairing"] == 0.1
    assert volspline.fit(data, 1, fairing=0)[1]["fairing"] == 0
    with pytest.raises(volspline.InvalidInput, match="temperature|pressure"):
        volspline.fit(data, 1, attributes=["pressure"])


def test_fit_of_grid_data_uses_the_lattice_layout_with_fairing():
    # docs/fitting.md, "Grid data": every combination of the axes' values once.
    axis = np.linspace(0, 1, 10)
    x, y, z = np.meshgrid(axis, axis, axis, indexing="ij")
    p = np.column_stack([x.ravel(), y.ravel(), z.ravel()])
    data = {"points": p, "attributes": {"f": p[:, 0] * p[:, 1] + p[:, 2] ** 2}}
    volume, stats = volspline.fit(data, 2)
    assert stats["primary_knots_layout"] == "lattice" and stats["fairing"] == 0.1
    # A quadratic is reproduced by the degree-2 fit, fairing or not (the term vanishes on it).
    assert stats["attributes"]["f"]["max_abs"] < 1e-6


def test_generated_data_names_keep_their_parameters():
    # two-material:N:TILT is the data the command line fits for the same name: the tilt counts.
    straight, _ = volspline.fit("two-material:9", 1)
    tilted, _ = volspline.fit("two-material:9:0.37", 1)
    x = np.array([[0.3, 0.9, 0.5]])  # x + 0.37 y = 0.633 > 0.5 when tilted, 0.3 < 0.5 when not
    assert straight.evaluate(x)["attributes"]["material"][0] < 1.5 < tilted.evaluate(x)["attributes"]["material"][0]
    with pytest.raises(Exception, match="two-material:N:TILT"):
        volspline.fit("two-material:9:x", 1)


def test_fit_local_knot_step_moves_primary_knots_unless_told_not_to():
    # A degree-1 DMS spline interpolates at the primary knots whatever the sub-knots: only moving
    # primary knots lowers its error (docs/fitting.md, "The local step").
    axis = np.linspace(0, 1, 8)
    x, y, z = np.meshgrid(axis, axis, axis, indexing="ij")
    p = np.column_stack([x.ravel(), y.ravel(), z.ravel()])
    data = {"points": p, "attributes": {"f": p[:, 0] * p[:, 1]}}
    runs = {}
    for fixed in (False, True):
        _, stats = volspline.fit(data, 1, primary_knots=40, knots="optimise", knot_sweeps=3, fixed_primary_knots=fixed,
                                 judge_local_step_at_data=True)
        runs[fixed] = stats["knot_optimisation"]
        assert runs[fixed]["sweeps"] <= 3 and not runs[fixed]["judged_on_held_out"]
    assert runs[False]["primary_knots_moved"] > 0 and runs[True]["primary_knots_moved"] == 0
    assert runs[False]["sweeps_kept"] > 0
    assert runs[False]["normalised_mean_square_after"] < 0.95 * runs[False]["normalised_mean_square_before"]
    # By default a sweep is kept only if the error at the held-out eighth of the points falls.
    _, stats = volspline.fit(data, 1, primary_knots=40, knots="optimise", knot_sweeps=3)
    held = stats["knot_optimisation"]
    assert held["judged_on_held_out"]
    if held["sweeps_kept"] == 0:  # the fit given stays
        assert held["held_out_normalised_mean_square_after"] == held["held_out_normalised_mean_square_before"]
        assert held["normalised_mean_square_after"] == held["normalised_mean_square_before"]
    else:
        assert held["held_out_normalised_mean_square_after"] < held["held_out_normalised_mean_square_before"]
    with pytest.raises(volspline.InvalidInput, match="knot_sweeps"):
        volspline.fit(data, 1, knots="optimise", knot_sweeps=0)


def test_progress_reports_phases_and_raises_what_the_callback_raises():
    reports = []
    volspline.boundary(volspline.half_cylinder_sweep(), progress=lambda phase, fraction: reports.append((phase, fraction)))
    assert {"subdivision", "faces"} <= {phase for phase, _ in reports}
    for phase in {phase for phase, _ in reports}:
        fractions = [f for p, f in reports if p == phase]
        assert all(0 <= f <= 1 for f in fractions) and fractions == sorted(fractions)

    class Stop(Exception):
        pass

    def stop(phase, fraction):
        raise Stop(phase)

    with pytest.raises(Stop):
        volspline.check_jacobian(volspline.ball(1.0), progress=stop)
    with pytest.raises(volspline.InvalidInput, match="callable"):
        volspline.boundary(volspline.ball(1.0), progress=3)


def test_long_calls_release_the_gil():
    # With a long switch interval a thread that wants the GIL gets it only when the holder
    # releases it: if evaluate kept the GIL, the counting thread could not run during the call.
    volume = volspline.ball(1.0)
    t = np.random.default_rng(5).random((300000, 3))
    count = [0]
    done = threading.Event()

    def spin():
        while not done.is_set():
            count[0] += 1

    interval = sys.getswitchinterval()
    sys.setswitchinterval(0.5)
    try:
        thread = threading.Thread(target=spin)
        thread.start()
        before = count[0]
        volume.evaluate(t)
        during = count[0] - before
        done.set()
        thread.join()
    finally:
        sys.setswitchinterval(interval)
    assert during > 1000


def test_the_example_tour_runs(tmp_path):
    import os
    import pathlib
    import subprocess

    source = pathlib.Path(os.environ.get("VOLSPLINE_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
    result = subprocess.run([sys.executable, str(source / "examples" / "python" / "tour.py"), str(tmp_path)],
                            capture_output=True, text=True, env=dict(os.environ))
    assert result.returncode == 0, result.stderr
    assert "envelope: closed True volume 8.5 exact 8.5" in result.stdout
    for name in ["ball-slices.png", "boundary.png", "envelope.png", "xray.png", "isosurface.png", "ball.json",
                 "ball.xml", "boundary.ply", "boundary.vtu"]:
        assert (tmp_path / name).stat().st_size > 0, name
