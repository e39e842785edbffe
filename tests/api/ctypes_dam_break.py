"""The library from Python through ctypes alone (Debian's python3, no other package): the seed's
dam break at 20 x 40 particles set up, stepped and read back.

    python3 tests/api/ctypes_dam_break.py LIBRYUSHI_SO CASES_DIR OUTPUT_DIR

Exit status 0 when every check holds; 1 with the failed ones on stderr.
"""
import ctypes
import sys

lib_path, cases, out = sys.argv[1:4]
lib = ctypes.CDLL(lib_path)
c_double_p = ctypes.POINTER(ctypes.c_double)
c_int64_p = ctypes.POINTER(ctypes.c_int64)
lib.ry_last_error.restype = ctypes.c_char_p
lib.ry_version.restype = ctypes.c_char_p
lib.ry_sim_time.restype = ctypes.c_double
lib.ry_sim_count.restype = ctypes.c_size_t
lib.ry_sim_step_count.restype = ctypes.c_long
lib.ry_sim_scheme.restype = ctypes.c_char_p
for name in ("ry_sim_time", "ry_sim_count", "ry_sim_step_count", "ry_sim_dimension",
             "ry_sim_scheme", "ry_sim_destroy", "ry_sim_step", "ry_sim_advance_to"):
    getattr(lib, name).argtypes = [ctypes.c_void_p] + (
        [ctypes.POINTER(ctypes.c_double)] if name == "ry_sim_step" else
        [ctypes.c_double] if name == "ry_sim_advance_to" else [])
lib.ry_sim_load.argtypes = [ctypes.POINTER(ctypes.c_void_p), ctypes.c_char_p, ctypes.c_int,
                            ctypes.POINTER(ctypes.c_char_p), ctypes.c_char_p]
lib.ry_sim_field.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.POINTER(c_double_p),
                             ctypes.POINTER(ctypes.c_size_t)]
lib.ry_sim_int_field.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.POINTER(c_int64_p),
                                 ctypes.POINTER(ctypes.c_size_t)]
lib.ry_sim_probe.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.POINTER(ctypes.c_double)]

failed = []


def check(ok, what):
    if not ok:
        failed.append(what)


def field(sim, name, kind=c_double_p, fn=None):
    data, n = kind(), ctypes.c_size_t()
    rc = (fn or lib.ry_sim_field)(sim, name.encode(), ctypes.byref(data), ctypes.byref(n))
    if rc != 0:
        raise SystemExit("field %s: %s" % (name, lib.ry_last_error().decode()))
    return [data[i] for i in range(n.value)]


# A case error comes back as the exit-code class with the file and key named.
sim = ctypes.c_void_p()
bad = (ctypes.c_char_p * 1)(b"time.nonsense=1")
rc = lib.ry_sim_load(ctypes.byref(sim), (cases + "/dam_break_seed.yaml").encode(), 1, bad,
                     out.encode())
msg = lib.ry_last_error().decode()
check(rc == 2 and "time.nonsense" in msg, "bad --set key: rc %d, message %r" % (rc, msg))
lib.ry_sim_create.argtypes = [ctypes.POINTER(ctypes.c_void_p), ctypes.c_char_p, ctypes.c_char_p,
                              ctypes.c_int, ctypes.POINTER(ctypes.c_char_p), ctypes.c_char_p]
text = open(cases + "/dam_break_seed.yaml").read().replace("spacing: 0.00625", "spacing: -1")
line = text[:text.index("spacing: -1")].count("\n") + 1
rc = lib.ry_sim_create(ctypes.byref(sim), text.encode(), b"mine.yaml", 0, None, out.encode())
msg = lib.ry_last_error().decode()
check(rc == 2 and ("mine.yaml:%d" % line) in msg and "spacing" in msg,
      "bad value in a case text: rc %d, message %r (want mine.yaml:%d and the key)" % (rc, msg, line))

sets = (ctypes.c_char_p * 3)(b"spacing=0.0125", b"time.end=0.05", b"output.vtk=false")
rc = lib.ry_sim_load(ctypes.byref(sim), (cases + "/dam_break_seed.yaml").encode(), 3, sets,
                     out.encode())
if rc != 0:
    raise SystemExit("load: %s" % lib.ry_last_error().decode())
check(lib.ry_sim_scheme(sim) == b"wcsph" and lib.ry_sim_dimension(sim) == 2, "scheme, dimension")
# 20 x 40 fluid particles of 1000 kg/m^3 x 0.0125^2 m^2 in a tank of three wall layers
count = lib.ry_sim_count(sim)
check(count == 1340, "particles: %d, want 1340" % count)
dt = ctypes.c_double()
for _ in range(10):
    check(lib.ry_sim_step(sim, ctypes.byref(dt)) == 0 and dt.value > 0, "step")
check(lib.ry_sim_step_count(sim) == 10, "10 steps")
check(lib.ry_sim_advance_to(sim, 0.02) == 0 and abs(lib.ry_sim_time(sim) - 0.02) < 1e-12,
      "advance to 0.02 s: t = %r" % lib.ry_sim_time(sim))
kind = field(sim, "kind", c_int64_p, lib.ry_sim_int_field)
mass = field(sim, "mass")
fluid = [m for m, k in zip(mass, kind) if k == 0]
check(len(fluid) == 800, "fluid particles: %d, want 800" % len(fluid))
total = sum(fluid)
check(abs(total - 125.0) < 1e-9, "fluid mass %.12g kg/m, want 125 (1000 x 0.25 x 0.5)" % total)
probe = ctypes.c_double()
check(lib.ry_sim_probe(sim, b"mass", ctypes.byref(probe)) == 0 and abs(probe.value - total) < 1e-9,
      "probe mass: %r" % probe.value)
ys = field(sim, "y")
check(len(ys) == count and max(y for y, k in zip(ys, kind) if k == 0) < 0.5 + 1e-3,
      "the column falls (highest fluid particle below 0.501 m)")
lib.ry_sim_destroy(sim)

if failed:
    for f in failed:
        print("ctypes: FAIL: " + f, file=sys.stderr)
    sys.exit(1)
print("ctypes: ryushi %s through libryushi.so: all checks hold" % lib.ry_version().decode())
