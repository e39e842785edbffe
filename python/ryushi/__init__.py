"""ryushi from Python: set a case up, advance it, read its particles as NumPy arrays.

    import ryushi
    with ryushi.Simulation.from_file("cases/dam_break_seed.yaml", output="out/db",
                                     set={"spacing": 0.0125, "time.end": 0.3}) as sim:
        sim.run_until(0.2)
        x = sim.field("position")

docs/python.md documents the package; it calls the shared library libryushi.so (ryushi.h)
through ctypes.
"""
from ._io import Particles, read_pvd, read_series, read_vtp
from ._lib import lib as _lib
from ._simulation import KINDS, Error, FieldInfo, Simulation, probes

__version__ = _lib.ry_version().decode()
library = _lib._name  # the path of the libryushi.so in use
__all__ = ["Simulation", "Error", "FieldInfo", "Particles", "KINDS", "probes", "read_series",
           "read_vtp", "read_pvd", "library", "__version__"]
