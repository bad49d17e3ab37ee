"""epicycle: load sharing of planetary spur-gear stages with manufacturing errors.

Python bindings of epicycle's C++ libraries (docs/python.md). Every name carries its unit
(carrier_deg, te_urad, force_N); results are `Result` objects with numpy arrays.

    import epicycle
    scene = epicycle.Scene.load("scenes/paper_stage_runout.toml")
    r = epicycle.quasistatic(scene, range="planet", positions=120)
    r.lsr            # (positions, planets) load-sharing ratios [-]
    r.summary.k_gamma

Bad input raises ValueError with the command line's message; a computation that failed raises
ComputationError, whose `.result` holds what was computed.
"""

import types as _types

import numpy as _np


class Result(_types.SimpleNamespace):
    """A driver's results: attributes named with their units (numpy arrays, numbers, lists).

    Parameters
    ----------
    **fields
        The results by name, each name with its unit (carrier_deg, te_urad, force_N).
    """

    def __repr__(self):
        def show(v):
            if isinstance(v, _np.ndarray):
                return f"array{v.shape}"
            if isinstance(v, list) and len(v) > 4:
                return f"list[{len(v)}]"
            if isinstance(v, Result):
                return "Result(...)"
            return repr(v)

        fields = ", ".join(f"{k}={show(v)}" for k, v in self.__dict__.items())
        return f"Result({fields})"


class ComputationError(RuntimeError):
    """A computation that did not succeed (failed positions, a run that stopped early, a failed
    solve).

    Parameters
    ----------
    message : str
        What failed.
    result : Result or None, default None
        What was computed (also the attribute `result`).
    """

    def __init__(self, message, result=None):
        super().__init__(message)
        self.result = result


class ContactFailure(ComputationError):
    """A run stopped by a contact solve that failed where it could not step around it (status
    "contact-failure"), or whose quasi-static start did not converge."""


class IntegratorFailure(ComputationError):
    """A run the integrator gave up (error test, Newton iteration, step count; status
    "integrator-failure")."""


class TimeLimitReached(ComputationError):
    """A run whose wall-time budget was spent (status "time-limit"); `.result` holds the steps
    computed until then."""


class GeometryFailure(ComputationError):
    """A run in which a member swung past where its meshes can be evaluated, or whose start
    found a planet separated from a member (status "geometry")."""


class BadSampledValue(ComputationError):
    """A study case whose sampled input broke a rule of the scene, so that it was not run (status
    "bad-sampled-value")."""


from ._epicycle import (  # noqa: E402  (the classes above are used by the module)
    ContactProblem,
    QuasiStaticPositions,
    Scene,
    compare_backends,
    compare_solutions,
    contact_backends,
    contact_residuals,
    contacts,
    dynamic,
    geometry,
    mesh_stiffness,
    modes,
    periodic_branch,
    quasistatic,
    quasistatic_positions,
    read_contact_problem,
    sobol_indices,
    solve_contact,
    speed_grid,
    speed_sweep,
    study,
)
from . import _epicycle  # noqa: E402


# Python functions around the module's study_part and study_merge: a scheduler sends a task's
# function to its workers by pickling it, which works for a module-level Python function (by
# name) and not for a compiled one.
def study_part(path, *, cases=None, shard=None, out_dir, threads=1, cache_dir=None,
               progress=None):
    return _epicycle.study_part(path, cases=cases, shard=shard, out_dir=out_dir, threads=threads,
                                cache_dir=cache_dir, progress=progress)


def study_merge(parts, *, out_dir, study=None):
    return _epicycle.study_merge(parts, out_dir=out_dir, study=study)


study_part.__doc__ = _epicycle.study_part.__doc__
study_merge.__doc__ = _epicycle.study_merge.__doc__

__all__ = [
    "BadSampledValue",
    "ComputationError",
    "ContactFailure",
    "GeometryFailure",
    "IntegratorFailure",
    "TimeLimitReached",
    "ContactProblem",
    "QuasiStaticPositions",
    "Result",
    "Scene",
    "compare_backends",
    "compare_solutions",
    "contact_backends",
    "contact_residuals",
    "contacts",
    "dynamic",
    "geometry",
    "mesh_stiffness",
    "modes",
    "periodic_branch",
    "quasistatic",
    "quasistatic_positions",
    "read_contact_problem",
    "sobol_indices",
    "solve_contact",
    "speed_grid",
    "speed_sweep",
    "study",
    "study_merge",
    "study_part",
]
