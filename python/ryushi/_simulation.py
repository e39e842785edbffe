"""ryushi.Simulation: a case set up, advanced and read through libryushi.so."""
import collections
import ctypes
import signal
import sys
import threading
import time

import numpy as np

from ._lib import c_char_pp, c_double_p, c_int64_p, lib, progress_fn

# Vector fields as the particle set stores them: one array of doubles per component.
VECTORS = {
    "position": ("x", "y", "z"),
    "velocity": ("vx", "vy", "vz"),
    "acceleration": ("ax", "ay", "az"),
}
INT_FIELDS = ("id", "kind", "material")
KINDS = {"fluid": 0, "wall": 1, "solid": 2, "inflow": 3, "outflow": 4}

FieldInfo = collections.namedtuple("FieldInfo", "name components unit dtype")
FieldInfo.__doc__ = """A field of the particles: its name (what Simulation.field takes), its
number of components (1, or the dimension for a vector), its unit and its NumPy type."""


class Error(RuntimeError):
    """A failed call of the library. str(e) is its message (for a case error: the file, line and
    key); e.code the program's exit-code class (2 bad input, 3 input/output, 4 unstable run,
    130 interrupted, 1 internal) and e.kind the error's kind in words ("value out of range",
    "i/o error", "simulation unstable", ...)."""

    __module__ = "ryushi"

    def __init__(self, message, code=1, kind="error"):
        super().__init__(message)
        self.code = code
        self.kind = kind


def _check(rc):
    if rc != 0:
        raise Error(lib.ry_last_error().decode(errors="replace"), rc,
                    lib.ry_last_error_kind().decode(errors="replace"))


def _set_value(v):
    """A Python value as `--set` takes it: true/false, [a,b,...], numbers to full precision."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (list, tuple, np.ndarray)):
        return "[" + ",".join(_set_value(x) for x in v) + "]"
    if isinstance(v, (float, np.floating)):
        return repr(float(v))
    return str(v)


def _sets(overrides):
    """Overrides, a dict {key: value} or a list of "key=value" strings, as a C array."""
    if overrides is None:
        text = []
    elif isinstance(overrides, dict):
        text = ["%s=%s" % (k, _set_value(v)) for k, v in overrides.items()]
    else:
        text = [str(s) for s in overrides]
    arr = (ctypes.c_char_p * max(len(text), 1))(*[t.encode() for t in text])
    return len(text), arr


def probes():
    """The probes Simulation.probe takes, {name: what it measures}, as `ryushi probes` lists."""
    out = {}
    i = 0
    while True:
        name = lib.ry_probe_name(i)
        if name is None:
            return out
        out[name.decode()] = lib.ry_probe_summary(i).decode()
        i += 1


class Simulation:
    """A simulation of a case, advanced from Python.

    Build one with Simulation.from_file(path, ...) or Simulation.from_yaml(text, ...) (or
    Simulation(path, ...), the same as from_file). Overrides `set` are a dict {key: value} (or
    strings "key=value") as the program's --set takes them; `output` is the output folder
    (default: the case's output.folder); `threads` the OpenMP threads of its steps (results do
    not depend on it). Use it as a context manager, or call close().

    The arrays that field() returns for a single field are views of the simulation's memory,
    read-only, and valid only until the next call that steps (step, run_until, run, restart)
    or closes it: copy them (np.array(a)) to keep them. Vector fields (position, velocity,
    acceleration) are assembled from their components and so are copies.
    """

    def __init__(self, case, output=None, threads=None, set=None, _text=None, _name=None):
        self._h = ctypes.c_void_p()
        self._progress_cb = None
        nset, arr = _sets(set)
        out = output.encode() if output is not None else None
        if _text is None:
            rc = lib.ry_sim_load(ctypes.byref(self._h), str(case).encode(), nset, arr, out)
        else:
            rc = lib.ry_sim_create(ctypes.byref(self._h), _text.encode(), _name.encode(), nset,
                                   arr, out)
        _check(rc)
        if threads is not None:
            self.set_threads(threads)

    @classmethod
    def from_file(cls, path, output=None, threads=None, set=None):
        """A simulation of the case file at path."""
        return cls(path, output=output, threads=threads, set=set)

    @classmethod
    def from_yaml(cls, text, name="case.yaml", output=None, threads=None, set=None):
        """A simulation of a case given as text; name stands for the file in messages and
        names the output files."""
        return cls(None, output=output, threads=threads, set=set, _text=text, _name=name)

    # lifetime
    def close(self):
        """Frees the simulation; its arrays and the handle are invalid afterwards."""
        if self._h:
            lib.ry_sim_destroy(self._h)
            self._h = ctypes.c_void_p()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def __del__(self):
        if getattr(self, "_h", None):
            self.close()

    def _handle(self):
        if not self._h:
            raise Error("the simulation is closed", 2, "input error")
        return self._h

    def __repr__(self):
        if not self._h:
            return "<ryushi.Simulation (closed)>"
        return "<ryushi.Simulation %s %dD, %d particles, t = %.6g s of %.6g s>" % (
            self.scheme, self.dimension, self.n, self.t, self.end_time)

    # advancing
    def set_threads(self, threads):
        """OpenMP threads for the steps (0: the OpenMP default)."""
        _check(lib.ry_sim_set_threads(self._handle(), int(threads)))

    def step(self):
        """One time step; returns its length in seconds (0.0 once the case has ended)."""
        dt = ctypes.c_double()
        self._stepping(lambda: lib.ry_sim_step(self._handle(), ctypes.byref(dt)), None)
        return dt.value

    def run_until(self, t, progress=None):
        """Steps until the simulated time reaches t (the last step lands on it) or the case
        ends. progress: a bar on stderr (default: when stderr is a terminal)."""
        self._stepping(lambda: lib.ry_sim_advance_to(self._handle(), float(t)), progress)

    def run(self, progress=None):
        """Runs to the case's end with its outputs and checkpoints. progress: a bar on stderr
        (default: when stderr is a terminal). Ctrl-C stops after the current step, with the
        state checkpointed, and raises KeyboardInterrupt."""
        self._stepping(lambda: lib.ry_sim_run(self._handle()), progress)

    def _stepping(self, call, progress):
        """Runs call with a progress hook that draws the bar; Ctrl-C (SIGINT, in the main
        thread) asks the library to stop after the current step, and then raises
        KeyboardInterrupt. The hook, called from the steps' loop, is where Python gets to run
        its signal handlers while the library works."""
        h = self._handle()
        show = sys.stderr.isatty() if progress is None else bool(progress)
        interrupted = []

        def on_sigint(_signum, _frame):
            interrupted.append(True)
            lib.ry_sim_request_stop(h)

        def hook(_ctx, t, t_end, step, dt, rate, eta):
            if show:
                frac = min(t / t_end, 1.0) if t_end > 0 else 0.0
                left = time.strftime("%H:%M:%S", time.gmtime(eta)) if 0 <= eta < 8.64e6 else "?"
                sys.stderr.write("\r[%-30s] t = %.4g / %.4g s  step %d  %.3g particle-steps/s  "
                                 "%s left " % ("#" * int(30 * frac), t, t_end, step, rate, left))
                sys.stderr.flush()

        cb = progress_fn(hook)
        _check(lib.ry_sim_set_progress(h, cb, None, 0.5 if show else 0.2))
        main = threading.current_thread() is threading.main_thread()
        before = signal.signal(signal.SIGINT, on_sigint) if main else None
        try:
            rc = call()
        finally:
            if main:
                signal.signal(signal.SIGINT, before)
            lib.ry_sim_set_progress(h, progress_fn(), None, 0.0)
            if show:
                sys.stderr.write("\n")
        if interrupted:
            raise KeyboardInterrupt("ryushi: stopped after step %d at t = %.6g s (checkpointed)"
                                    % (self.steps, self.t))
        _check(rc)

    def restart(self, folder):
        """Continues from the newest sound checkpoint in folder (an output folder or its
        checkpoints/); returns the file taken."""
        used = ctypes.create_string_buffer(4400)
        _check(lib.ry_sim_restart(self._handle(), str(folder).encode(), used, len(used), None, 0))
        return used.value.decode()

    # state
    @property
    def t(self):
        """The simulated time [s]."""
        return lib.ry_sim_time(self._handle())

    @property
    def end_time(self):
        """The case's end time [s]."""
        return lib.ry_sim_end_time(self._handle())

    @property
    def steps(self):
        """Steps taken since the start of the case."""
        return lib.ry_sim_step_count(self._handle())

    @property
    def n(self):
        """Particles of every kind (fluid, wall, solid, inflow and outflow buffers)."""
        return lib.ry_sim_count(self._handle())

    @property
    def dimension(self):
        return lib.ry_sim_dimension(self._handle())

    @property
    def scheme(self):
        return lib.ry_sim_scheme(self._handle()).decode()

    @property
    def output_dir(self):
        return lib.ry_sim_output_dir(self._handle()).decode()

    @property
    def stop_reason(self):
        """Why the run stopped before its end time (time.stop_when), or ""."""
        return lib.ry_sim_stop_reason(self._handle()).decode()

    def _names(self):
        h = self._handle()
        count = lib.ry_sim_field_names(h, None, 0)
        if count < 0:
            _check(1)
        names = (ctypes.c_char_p * count)()
        lib.ry_sim_field_names(h, ctypes.cast(names, c_char_pp), count)
        return [s.decode() for s in names]

    def fields(self):
        """The fields field() takes, as FieldInfo(name, components, unit, dtype): the vectors
        position, velocity and acceleration (components: the dimension), then every field of
        doubles, then id, kind and material (int64)."""
        h = self._handle()
        names = self._names()
        dim = self.dimension
        out = [FieldInfo(v, dim, lib.ry_sim_field_unit(h, c[0].encode()).decode(), np.float64)
               for v, c in VECTORS.items() if c[0] in names]
        for s in names:
            out.append(FieldInfo(s, 1, lib.ry_sim_field_unit(h, s.encode()).decode(),
                                 np.int64 if s in INT_FIELDS else np.float64))
        return out

    def field(self, name):
        """The particles' values of a field: shape (n,) for a single field (a read-only view,
        valid until the next step), (n, dimension) for position, velocity and acceleration
        (a copy). fields() lists the names."""
        h = self._handle()
        if name in VECTORS:
            return np.stack([self.field(c) for c in VECTORS[name][:self.dimension]], axis=1)
        n = ctypes.c_size_t()
        if name in INT_FIELDS:
            ptr = c_int64_p()
            _check(lib.ry_sim_int_field(h, name.encode(), ctypes.byref(ptr), ctypes.byref(n)))
            dtype = np.int64
        else:
            ptr = c_double_p()
            _check(lib.ry_sim_field(h, name.encode(), ctypes.byref(ptr), ctypes.byref(n)))
            dtype = np.float64
        if n.value == 0:
            return np.empty(0, dtype)
        a = np.ctypeslib.as_array(ptr, shape=(n.value,))
        a.flags.writeable = False
        return a

    def probe(self, name):
        """A measured quantity by name (ryushi.probes() lists them), as series.csv has it."""
        v = ctypes.c_double()
        _check(lib.ry_sim_probe(self._handle(), name.encode(), ctypes.byref(v)))
        return v.value

    def stat(self, name):
        """A statistic of the run: "steps", "wall_s" and "particle_steps_per_s" of the last
        call that stepped, "outputs", "searches", "bytes_per_particle", or the scheme's own
        (report() lists those)."""
        v = ctypes.c_double()
        _check(lib.ry_sim_stat(self._handle(), name.encode(), ctypes.byref(v)))
        return v.value

    def report(self):
        """The scheme's statistics, {name: value} (e.g. the pressure solver's iterations)."""
        buf = ctypes.create_string_buffer(8192)
        _check(lib.ry_sim_report(self._handle(), buf, len(buf)))
        out = {}
        for item in buf.value.decode().split():
            k, _, v = item.partition("=")
            try:
                out[k] = float(v)
            except ValueError:
                out[k] = v
        return out

    # output
    def write_output(self):
        """Writes the current state as an output (a VTK file, its .pvd entry and a row of
        series.csv) and a checkpoint."""
        _check(lib.ry_sim_write_output(self._handle()))

    def checkpoint(self):
        """Writes a checkpoint into the output folder's checkpoints/."""
        _check(lib.ry_sim_checkpoint(self._handle()))
