"""Access to the core: FMUs through fmpy (:mod:`.model`, :mod:`.instance`), FMUs shipped to Dask
workers (:mod:`.worker`) and the core's own command line ``target/libs/georod``
(:mod:`.core_command`). Nothing here knows about analyses; nothing here reads the bytes of a
serialized FMU state (they travel between instances as an opaque blob)."""

from georod_tools.fmu.instance import FMI2_STATUS, FmuError, Instance, lend
from georod_tools.fmu.model import FmuModel, Variable

__all__ = ["FMI2_STATUS", "FmuError", "FmuModel", "Instance", "Variable", "lend"]
