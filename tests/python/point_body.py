"""A floating body that translates only (surge, sway, heave), built by
pythonfmu: another tool's body in a slender mooring (issue 47).

Its ports are those of slender's `body` for three fairleads f1, f2, f3:
inputs `f<k>_force_x|y|z` (N, the lines' pull, global), outputs the reference
point's `x`, `y`, `z` (m) and `velocity_x|y|z`, and per fairlead its
`position`, `velocity` and `acceleration` (x, y, z). Per axis: mass plus added
mass, a linear restoring about the rest position `rest_x|y|z`, linear damping
and a constant net load (buoyancy less weight in z); the trapezoidal rule, as
slender's body steps, solved in closed form (the system is linear). Every
quantity of its state is a registered variable, so pythonfmu's
`--handle-state` saves and restores it for an iterative master.
"""

from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Real

AXES = ("x", "y", "z")
FAIRLEADS = ("f1", "f2", "f3")


class PointBody(Fmi2Slave):
    author = "slender tests"
    description = "a floating body in surge, sway and heave with three fairleads"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        parameters = {}
        for a in AXES:
            parameters[f"mass_{a}"] = 1.0
            parameters[f"stiffness_{a}"] = 0.0
            parameters[f"damping_{a}"] = 0.0
            parameters[f"net_force_{a}"] = 0.0
            parameters[f"rest_{a}"] = 0.0
            parameters[f"start_{a}"] = 0.0
        for f in FAIRLEADS:
            for a in AXES:
                parameters[f"{f}_offset_{a}"] = 0.0
        for name, value in parameters.items():
            setattr(self, name, value)
            self.register_variable(
                Real(name, causality=Fmi2Causality.parameter, variability=Fmi2Variability.fixed)
            )
        for f in FAIRLEADS:
            for a in AXES:
                setattr(self, f"{f}_force_{a}", 0.0)
                self.register_variable(Real(f"{f}_force_{a}", causality=Fmi2Causality.input))
        outputs = [f"{a}" for a in AXES] + [f"velocity_{a}" for a in AXES]
        outputs += [f"acceleration_{a}" for a in AXES]
        for f in FAIRLEADS:
            for what in ("position", "velocity", "acceleration"):
                outputs += [f"{f}_{what}_{a}" for a in AXES]
        for name in outputs:
            setattr(self, name, 0.0)
            self.register_variable(Real(name, causality=Fmi2Causality.output))

    def load(self, a):
        """The load along axis `a` but the inertial and velocity ones, at the
        current position and inputs."""
        pull = sum(getattr(self, f"{f}_force_{a}") for f in FAIRLEADS)
        spring = getattr(self, f"stiffness_{a}") * (getattr(self, a) - getattr(self, f"rest_{a}"))
        return getattr(self, f"net_force_{a}") + pull - spring

    def fairleads(self):
        for f in FAIRLEADS:
            for a in AXES:
                setattr(self, f"{f}_position_{a}", getattr(self, a) + getattr(self, f"{f}_offset_{a}"))
                setattr(self, f"{f}_velocity_{a}", getattr(self, f"velocity_{a}"))
                setattr(self, f"{f}_acceleration_{a}", getattr(self, f"acceleration_{a}"))

    def enter_initialization_mode(self):
        for a in AXES:
            setattr(self, a, getattr(self, f"start_{a}"))
            setattr(self, f"velocity_{a}", 0.0)
        self.fairleads()

    def exit_initialization_mode(self):
        # The acceleration under the lines' pull the master settled.
        for a in AXES:
            setattr(self, f"acceleration_{a}", self.load(a) / getattr(self, f"mass_{a}"))
        self.fairleads()

    def do_step(self, current_time, step_size):
        h = step_size
        for a in AXES:
            m = getattr(self, f"mass_{a}")
            c = getattr(self, f"damping_{a}")
            k = getattr(self, f"stiffness_{a}")
            x0, v0 = getattr(self, a), getattr(self, f"velocity_{a}")
            a0 = getattr(self, f"acceleration_{a}")
            pull = sum(getattr(self, f"{f}_force_{a}") for f in FAIRLEADS)
            rest = getattr(self, f"rest_{a}")
            # m a1 = F - c v1 - k (x1 - rest), v1 = v0 + h (a0 + a1) / 2,
            # x1 = x0 + h v0 + h^2 (a0 + a1) / 4.
            rhs = getattr(self, f"net_force_{a}") + pull - c * (v0 + 0.5 * h * a0)
            rhs -= k * (x0 + h * v0 + 0.25 * h * h * a0 - rest)
            a1 = rhs / (m + 0.5 * h * c + 0.25 * h * h * k)
            v1 = v0 + 0.5 * h * (a0 + a1)
            setattr(self, a, x0 + 0.5 * h * (v0 + v1))
            setattr(self, f"velocity_{a}", v1)
            setattr(self, f"acceleration_{a}", a1)
        self.fairleads()
        return True
