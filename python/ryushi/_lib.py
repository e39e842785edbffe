"""The shared library libryushi.so and the prototypes of its interface (include/ryushi/ryushi.h)."""
import ctypes
import ctypes.util
import os

c_double_p = ctypes.POINTER(ctypes.c_double)
c_int64_p = ctypes.POINTER(ctypes.c_int64)
c_char_pp = ctypes.POINTER(ctypes.c_char_p)
handle_p = ctypes.POINTER(ctypes.c_void_p)
progress_fn = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_double, ctypes.c_double,
                               ctypes.c_long, ctypes.c_double, ctypes.c_double, ctypes.c_double)

_PROTOTYPES = {
    # name: (result, arguments)
    "ry_sim_load": (ctypes.c_int, [handle_p, ctypes.c_char_p, ctypes.c_int, c_char_pp,
                                   ctypes.c_char_p]),
    "ry_sim_create": (ctypes.c_int, [handle_p, ctypes.c_char_p, ctypes.c_char_p, ctypes.c_int,
                                     c_char_pp, ctypes.c_char_p]),
    "ry_sim_restart": (ctypes.c_int, [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_char_p,
                                      ctypes.c_size_t, ctypes.c_char_p, ctypes.c_size_t]),
    "ry_sim_destroy": (None, [ctypes.c_void_p]),
    "ry_sim_set_threads": (ctypes.c_int, [ctypes.c_void_p, ctypes.c_int]),
    "ry_sim_step": (ctypes.c_int, [ctypes.c_void_p, c_double_p]),
    "ry_sim_advance_to": (ctypes.c_int, [ctypes.c_void_p, ctypes.c_double]),
    "ry_sim_run": (ctypes.c_int, [ctypes.c_void_p]),
    "ry_sim_request_stop": (None, [ctypes.c_void_p]),
    "ry_sim_set_progress": (ctypes.c_int, [ctypes.c_void_p, progress_fn, ctypes.c_void_p,
                                           ctypes.c_double]),
    "ry_sim_time": (ctypes.c_double, [ctypes.c_void_p]),
    "ry_sim_end_time": (ctypes.c_double, [ctypes.c_void_p]),
    "ry_sim_step_count": (ctypes.c_long, [ctypes.c_void_p]),
    "ry_sim_dimension": (ctypes.c_int, [ctypes.c_void_p]),
    "ry_sim_count": (ctypes.c_size_t, [ctypes.c_void_p]),
    "ry_sim_scheme": (ctypes.c_char_p, [ctypes.c_void_p]),
    "ry_sim_output_dir": (ctypes.c_char_p, [ctypes.c_void_p]),
    "ry_sim_field": (ctypes.c_int, [ctypes.c_void_p, ctypes.c_char_p, ctypes.POINTER(c_double_p),
                                    ctypes.POINTER(ctypes.c_size_t)]),
    "ry_sim_int_field": (ctypes.c_int, [ctypes.c_void_p, ctypes.c_char_p,
                                        ctypes.POINTER(c_int64_p),
                                        ctypes.POINTER(ctypes.c_size_t)]),
    "ry_sim_field_names": (ctypes.c_int, [ctypes.c_void_p, c_char_pp, ctypes.c_int]),
    "ry_sim_field_unit": (ctypes.c_char_p, [ctypes.c_void_p, ctypes.c_char_p]),
    "ry_sim_probe": (ctypes.c_int, [ctypes.c_void_p, ctypes.c_char_p, c_double_p]),
    "ry_probe_name": (ctypes.c_char_p, [ctypes.c_int]),
    "ry_probe_summary": (ctypes.c_char_p, [ctypes.c_int]),
    "ry_sim_stat": (ctypes.c_int, [ctypes.c_void_p, ctypes.c_char_p, c_double_p]),
    "ry_sim_report": (ctypes.c_int, [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_size_t]),
    "ry_sim_stop_reason": (ctypes.c_char_p, [ctypes.c_void_p]),
    "ry_sim_write_output": (ctypes.c_int, [ctypes.c_void_p]),
    "ry_sim_checkpoint": (ctypes.c_int, [ctypes.c_void_p]),
    "ry_last_error": (ctypes.c_char_p, []),
    "ry_last_error_kind": (ctypes.c_char_p, []),
    "ry_version": (ctypes.c_char_p, []),
}


def _candidates():
    """Where libryushi.so is looked for, in order: $RYUSHI_LIBRARY; beside the package in an
    installation (PREFIX/lib, the package under PREFIX/lib/python3/dist-packages); the build
    folder of the repository the package lives in; the system's library path."""
    env = os.environ.get("RYUSHI_LIBRARY")
    if env:
        yield env
        return
    here = os.path.dirname(os.path.abspath(__file__))
    for up in (os.path.join(here, "..", "..", ".."), os.path.join(here, "..", "..", "build")):
        yield os.path.normpath(os.path.join(up, "libryushi.so"))
    found = ctypes.util.find_library("ryushi")
    if found:
        yield found


def load():
    """The library with its prototypes declared; ImportError naming where it was looked for."""
    tried = []
    for path in _candidates():
        tried.append(path)
        if os.sep in path and not os.path.exists(path):
            continue
        try:
            lib = ctypes.CDLL(path)
        except OSError:
            continue
        for name, (res, args) in _PROTOTYPES.items():
            fn = getattr(lib, name)
            fn.restype = res
            fn.argtypes = args
        return lib
    raise ImportError("ryushi: libryushi.so not found (looked for %s); build it with `make python`"
                      " or set RYUSHI_LIBRARY to its path" % ", ".join(tried))


lib = load()
