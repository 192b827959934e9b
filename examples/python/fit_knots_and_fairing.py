"""Fitting scattered samples (Hua-He-Qin §5): fairing and the local knot step, judged against the
field the samples came from (docs/fitting.md, "Fairing" and "The local step").

    PYTHONPATH=build/python /usr/bin/python3 examples/python/fit_knots_and_fairing.py

A steep front sampled at 2,500 random points of the unit cube is fitted with 40 primary knots:
unfaired, with the default fairing (0.1), and with the local knot step judged on the held-out
eighth of the points and, for comparison, at the data. Each line gives the normalised mean
square error at the data and against the front at 20,000 random points of the domain.
"""
import numpy as np

import volspline

rng = np.random.default_rng(31)
points = rng.random((2500, 3))
probes = rng.random((20000, 3))


def front(p):
    return np.tanh(12 * (p[:, 0] + 0.3 * p[:, 1] - 0.6))


data = {"points": points, "attributes": {"f": front(points)}}


def report(name, **options):
    volume, stats = volspline.fit(data, 2, primary_knots=40, **options)
    e = volume.evaluate(probes)
    inside = e["inside"]
    truth = np.mean(((e["attributes"]["f"][inside] - front(probes[inside])) / 2) ** 2)
    line = f"{name:38s} data {stats['field_normalised_mean_square']:.2e}  truth {truth:.2e}"
    k = stats["knot_optimisation"]
    if k["sweeps"]:
        line += f"  ({k['sweeps_kept']} of {k['sweeps']} sweeps kept)"
    print(line)


report("fixed knots, unfaired", fairing=0)
report("fixed knots, default fairing")
report("local step, judged on held-out data", knots="optimise")
report("local step, judged at the data", knots="optimise", judge_local_step_at_data=True)
