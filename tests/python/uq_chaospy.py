"""Cross-check of slender-uq's sparse PCE with chaospy (tests/tests/uq_python.rs).

Reads a JSON file with the design (standard inputs in [-1, 1], one list per
point), the outputs and a polynomial order; fits chaospy's point-collocation
expansion (ordinary least squares on the full total-degree Legendre basis of
independent U(-1, 1) inputs) and prints its mean, variance and first-order and
total Sobol' indices as JSON.
"""

import json
import sys

import chaospy
import numpy


def main(path):
    with open(path) as f:
        data = json.load(f)
    xi = numpy.array(data["xi"]).T
    y = numpy.array(data["y"])
    dims = xi.shape[0]
    dist = chaospy.J(*[chaospy.Uniform(-1.0, 1.0) for _ in range(dims)])
    expansion = chaospy.generate_expansion(data["order"], dist, normed=True)
    model = chaospy.fit_regression(expansion, xi, y)
    out = {
        "mean": float(chaospy.E(model, dist)),
        "variance": float(chaospy.Var(model, dist)),
        "first": [float(v) for v in chaospy.Sens_m(model, dist)],
        "total": [float(v) for v in chaospy.Sens_t(model, dist)],
        "terms": len(expansion),
    }
    print(json.dumps(out))


if __name__ == "__main__":
    main(sys.argv[1])
