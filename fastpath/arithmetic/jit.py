"""One place for the numba options every kernel uses.

``fastmath`` stays off: the rigour of the lower-bound step and the error bounds of the gap
assume IEEE round-to-nearest arithmetic, which reassociation would break.

Compiled kernels are cached on disk (``cache=True``), but numba checks only the timestamp of the
file that defines a kernel, not of the kernels it calls from other modules: an edited callee
would silently keep its old machine code. So the cache lives in a directory named by a digest of
all of fastpath's sources (``CACHE_DIR``), under ``NUMBA_CACHE_DIR`` if set, else the user cache
directory (``CACHE_ROOT``). numba reads that setting when a kernel is decorated, so it is changed
only for that moment and other libraries' caches stay where they were.

Compile time (docs/performance.md). Nothing is compiled at import; a kernel compiles at its
first call, for the argument types of that call. Five choices keep that short:

* ``inline_jit`` helpers (the straight-line code of the ensembles' lanes) are compiled once
  each and marked for LLVM to inline (``forceinline``: LLVM's ``alwaysinline``), so that the
  loop over lanes still vectorises. numba's own ``inline="always"`` copied and typed their code
  again at every call site (four evaluations of a flight, each with its sines): most of the
  escape kernel's compile time.
* A call from compiled code is typed with the plain types of its arguments
  (``_called_from_compiled_code``), not one specialisation per constant value.
* A kernel has two dispatchers: the one Python calls, and one for compiled callers
  (``COMPILED_CALLERS``), compiled to LLVM IR only, which its callers link and inline: no
  CPython wrapper, no machine code of its own, nothing written to the cache (a caller's cached
  machine code holds it), and LLVM's module passes (inlining among them) left to the module of
  the kernel Python calls, which runs them once over everything it links. numba otherwise does
  all of this for every function it compiles, helpers included: about a third of a cold start.
* ``typed_overload`` chooses an implementation when the caller is typed, so that a loop
  compiled for one model (``fastpath.kernels.particle``) compiles no other model's code.
* No C-callable wrapper (``no_cfunc_wrapper``): numba otherwise builds one for every compiled
  function, for passing it to C or as a first-class function value, which no kernel does.

Two limits of numba that the kernels respect (numba 0.68 loses the writes otherwise, silently):
inside a ``prange`` loop an array held in a tuple (``fastpath.kernels.arrays``) is written only
through a called function, never as ``group.array[i] = ...`` in the loop body itself; and an
``overload`` (``fastpath.physics.model_of``) is not inlined into its caller (``inline="always"``
dropped writes to arrays unpacked from a tuple). LLVM still inlines and folds it.

Threads. The ensemble kernels run their groups of blocks in Python threads
(``fastpath.kernels.threads``). numba's ``workqueue`` threading layer (the fallback where
neither TBB nor OpenMP can be loaded) aborts the whole process (SIGABRT) when two Python threads
enter parallel code at once. ``parallel_jit`` kernels (the array calls of ``fastpath.api``, the
dynamics) are therefore called through a wrapper that holds one process-wide lock while numba
runs that layer (or has not chosen one yet); with TBB or OpenMP, which are safe to enter from
several threads, calls run concurrently. The kernels are entered from Python only.
"""

import functools
import hashlib
import os
import threading
import types as types_module
from pathlib import Path

import numba
import numpy as np
from numba.core import sigutils, types
from numba.core.compiler import CompilerBase, DefaultPassBuilder
from numba.core.compiler_machinery import register_pass
from numba.core.typed_passes import NativeLowering
from numba.extending import overload


def _cache_root():
    return os.environ.get("NUMBA_CACHE_DIR") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache"),
        "bouncer-verify",
        "numba",
    )


def _cache_dir():
    package = Path(__file__).resolve().parents[1]
    digest = hashlib.sha256()
    for path in sorted(package.rglob("*.py")):
        digest.update(path.relative_to(package).as_posix().encode() + b"\0" + path.read_bytes())
    return os.path.join(CACHE_ROOT, digest.hexdigest()[:16])


CACHE_ROOT = _cache_root()  # the caches of every version of fastpath's sources
CACHE_DIR = _cache_dir()


# every kernel's options (module docstring); the caching and wrappers differ by dispatcher
KERNEL_OPTIONS = {"nogil": True, "error_model": "numpy", "no_cfunc_wrapper": True}


def _cached_dispatcher(function, options):
    saved = numba.config.CACHE_DIR
    numba.config.CACHE_DIR = CACHE_DIR
    try:
        return numba.njit(cache=True, **KERNEL_OPTIONS, **options)(function)
    finally:
        numba.config.CACHE_DIR = saved


@register_pass(mutates_CFG=True, analysis_only=False)
class _LoweringForCompiledCallers(NativeLowering):
    """numba's lowering without machine code: the function's LLVM IR (after the function
    passes) for compiled callers to link and inline; nothing is made that Python could call."""

    _name = "lowering_for_compiled_callers"

    def run_pass(self, state):
        state.flags.no_compile = True
        super().run_pass(state)
        library = state.library
        library._finalize_final_module = functools.partial(_ir_only, library)
        library._optimize_final_module = _module_passes_left_to_the_caller
        entry = _not_callable_from_python(state.func_id.func_qualname)
        state.targetctx.insert_user_function(entry, state.cr.fndesc, [library])
        state.cr = state.cr._replace(cfunc=entry)
        return True


def _ir_only(library):
    """``CodeLibrary._finalize_final_module`` without adding the module to the execution engine
    (which would make its machine code): the module is only linked into callers. This and
    ``_LoweringForCompiledCallers`` use numba's private lowering and library methods (as of
    numba 0.68); ``tests/fastpath/test_compile_on_demand.py`` fails if they change."""
    library._finalize_dynamic_globals()
    library._verify_declare_only_symbols()
    library._finalized = True


def _module_passes_left_to_the_caller():
    """The module passes (inlining among them) run once, on the caller's linked module."""


def _not_callable_from_python(name):
    def entry(*args, **kws):
        raise TypeError(f"{name} is compiled for compiled callers only")
    return entry


class _CompilerForCompiledCallers(CompilerBase):
    def define_pipelines(self):
        pm = DefaultPassBuilder.define_nopython_pipeline(self.state)
        pm.passes = [(_LoweringForCompiledCallers if p is NativeLowering else p, d)
                     for p, d in pm.passes]
        pm.finalize()
        return [pm]


COMPILED_CALLERS = "_for_compiled_callers"  # the name's suffix of a kernel's second dispatcher


def _dispatcher_for_compiled_callers(function, options):
    """``function``'s dispatcher for compiled callers (``_LoweringForCompiledCallers``), under
    its own name (``COMPILED_CALLERS``) and never cached: its compilations are kept for typing
    and linking only, out of numba's table of what Python can call."""
    dispatcher = numba.njit(no_cpython_wrapper=True, pipeline_class=_CompilerForCompiledCallers,
                            **KERNEL_OPTIONS, **options)(_renamed(function, COMPILED_CALLERS))

    def add_overload(cres):
        dispatcher.overloads[tuple(cres.signature.args)] = cres

    dispatcher.add_overload = add_overload
    return dispatcher


def _cached_njit(**options):
    def decorate(function):
        dispatcher = _cached_dispatcher(function, options)
        if numba.config.DISABLE_JIT:  # NUMBA_DISABLE_JIT=1: numba returns the plain function
            return dispatcher
        return _called_from_compiled_code(dispatcher,
                                          _dispatcher_for_compiled_callers(function, options))

    return decorate


def _called_from_compiled_code(dispatcher, for_compiled_callers):
    """Have compiled callers of ``dispatcher`` call ``for_compiled_callers`` (the same function
    compiled without a CPython wrapper), with the plain types of their arguments.

    The wrapper, which converts Python objects to native values and back, is about half of a
    small function's compile time, and only a call from Python needs it: most kernels are
    called from other kernels only. A specialisation that the Python-facing dispatcher has
    already compiled (a kernel called from Python first) is used as it is, so a kernel called
    both ways compiles once for each way at most. Both are the same code with the same options:
    the same numbers either way.

    numba types a constant argument (``collide(phi, v, eps, GENERAL)``, an evaluation index 1,
    2, 3) as a literal of its value and compiles the callee once for each value; a variable of
    the same type shares one specialisation. The literal's value does not change the callee's
    arithmetic (it can only fold a branch, which LLVM does anyway where it inlines), so the
    calls are typed with the values' types (``numba.core.types.unliteral``): one compilation
    where there were up to six.
    """
    own_call_template, own_overload = dispatcher.get_call_template, dispatcher.get_overload

    def compiled_for_python(args):
        return tuple(args) in dispatcher.overloads

    def get_call_template(args, kws):
        args = tuple(types.unliteral(a) for a in args)
        kws = {k: types.unliteral(v) for k, v in kws.items()}
        if compiled_for_python(dispatcher.fold_argument_types(args, kws)[1]):
            return own_call_template(args, kws)
        return for_compiled_callers.get_call_template(args, kws)

    def get_overload(sig):
        if compiled_for_python(sigutils.normalize_signature(sig)[0]):
            return own_overload(sig)
        return for_compiled_callers.get_overload(sig)

    dispatcher.get_call_template, dispatcher.get_overload = get_call_template, get_overload
    dispatcher.for_compiled_callers = for_compiled_callers
    return dispatcher


_WORKQUEUE_LOCK = threading.Lock()


def _serialise():
    """Whether a parallel kernel must hold the lock (module docstring)."""
    try:
        return numba.threading_layer() == "workqueue"
    except ValueError:  # no parallel kernel has run yet: the layer is not chosen
        return True


PARALLEL_MIN = 4096  # elements below which a parallel kernel runs its serial compilation


def parallel_jit(function):
    """``numba.njit(parallel=True)`` (cached) for calls over at least PARALLEL_MIN elements (the
    length of the first array argument), called through the workqueue lock (module
    docstring); a smaller call runs the same function compiled without ``parallel``, where
    ``prange`` is ``range``: every element is computed alone either way (the kernels' ``prange``
    loops have no reductions), so the numbers are the same, and a first small call (the README's
    quick start) pays no parallel compile. The compiled dispatchers are the wrapper's
    ``kernel`` and ``serial_kernel``."""
    kernel = _cached_dispatcher(function, {"parallel": True})
    serial_kernel = _cached_dispatcher(_renamed(function, "_serial"), {})

    @functools.wraps(function)
    def call(*args):
        size = next((len(a) for a in args if isinstance(a, np.ndarray)), PARALLEL_MIN)
        if size < PARALLEL_MIN:
            return serial_kernel(*args)
        if _serialise():
            with _WORKQUEUE_LOCK:
                return kernel(*args)
        return kernel(*args)

    call.kernel, call.serial_kernel = kernel, serial_kernel
    return call


def _renamed(function, suffix):
    """A copy of ``function`` whose name ends in ``suffix``: numba's cache files are named by
    the function (and keyed by its code, not by the compile options), so the serial and the
    parallel compilation of one function need two names."""
    copy = types_module.FunctionType(function.__code__, function.__globals__,
                                     function.__name__ + suffix, function.__defaults__,
                                     function.__closure__)
    copy.__qualname__ = function.__qualname__ + suffix
    copy.__module__, copy.__doc__ = function.__module__, function.__doc__
    return copy


def typed_overload(function, prefer_literal=False):
    """``numba.extending.overload`` with the kernels' arithmetic options: the implementation
    that the decorated function returns for the argument types is what compiled callers of
    ``function`` run (the choice is made when they are typed; with ``prefer_literal`` a
    constant argument is seen as its value, ``numba.core.types.Literal``)."""
    return overload(function, jit_options={**KERNEL_OPTIONS, "no_cpython_wrapper": True},
                    prefer_literal=prefer_literal)


jit = _cached_njit()
# scalar helpers of the lockstep kernels: inlined by LLVM into the loop, so that it vectorises
inline_jit = _cached_njit(forceinline=True)
