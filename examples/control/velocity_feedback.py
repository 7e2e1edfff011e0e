"""The controller of examples/control/: velocity feedback, `force = gain * velocity`, as an FMI 2.0
Co-Simulation FMU built by pythonfmu (`pythonfmu build -f velocity_feedback.py`).

Coupled to a georod FMU's midspan velocity `v_mid` (along +e2) and control force `f_ctrl` (along
-e2), a positive gain makes the force oppose the motion: its power `-gain * v_mid**2` is never
positive, so the controller only removes energy (the FMU's `W_ctrl` goes negative)."""

from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Real


class VelocityFeedback(Fmi2Slave):
    author = "georod"
    description = "Velocity feedback: force = gain * velocity"

    def __init__(self, **kwargs) -> None:
        super().__init__(**kwargs)
        self.gain = 0.0
        self.velocity = 0.0
        self.force = 0.0
        self.register_variable(
            Real(
                "gain",
                causality=Fmi2Causality.parameter,
                variability=Fmi2Variability.tunable,
            )
        )
        self.register_variable(Real("velocity", causality=Fmi2Causality.input))
        self.register_variable(Real("force", causality=Fmi2Causality.output))

    def do_step(self, current_time: float, step_size: float) -> bool:
        self.force = self.gain * self.velocity
        return True
