"""A massless spring-damper to ground, built by pythonfmu (an external exporter).

Inputs: displacement (m), velocity (m/s) of the attachment point.
Output: force (N) on it, -(stiffness * displacement + damping * velocity).
Used by slender's tests to couple an FMU written by someone else's tool.
"""

from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Real


class SpringDamper(Fmi2Slave):
    author = "slender tests"
    description = "massless spring-damper to ground"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.stiffness = 50.0
        self.damping = 0.0
        self.displacement = 0.0
        self.velocity = 0.0
        self.force = 0.0
        self.register_variable(Real("stiffness", causality=Fmi2Causality.parameter,
                                    variability=Fmi2Variability.tunable))
        self.register_variable(Real("damping", causality=Fmi2Causality.parameter,
                                    variability=Fmi2Variability.tunable))
        self.register_variable(Real("displacement", causality=Fmi2Causality.input))
        self.register_variable(Real("velocity", causality=Fmi2Causality.input))
        self.register_variable(Real("force", causality=Fmi2Causality.output))

    def do_step(self, current_time, step_size):
        self.force = -(self.stiffness * self.displacement + self.damping * self.velocity)
        return True
