"""tumble: rigid-body dynamics in generalized coordinates, from Python.

The same C++ templates as the header-only library (include/tumble), compiled into one module;
NumPy arrays in and out; SI units and rad throughout.

- parameterizations: ``tumble.parameterization(name)`` or ``tumble.EulerZYX``, ... (all 16);
- bodies: ``tumble.RigidBody(parameterization, tumble.MassProperties.about_centroid(...),
  reference="centroid" | "offset" | "fixed_point")``;
- scenes: ``tumble.Scene()``, ``add``, ``add_gravity``, ``add_point_force``, ``add_moment``,
  ``add_spring``, ``add_spring_between``, ``add_user_load``, ``add_event`` (Python callables,
  called at every step); ``integrate`` (the front door, ``tumble::integrate``) and ``ensemble``
  (oneTBB, the GIL released);
- errors: ``ValueError`` for bad input, ``tumble.IntegrationError`` when an integration cannot
  go on (a Python load or event function that raised: ``reason`` ``'callback'``, its exception
  the ``__cause__``; an event action's exception reaches the caller unchanged).
"""

from ._tumble import *  # noqa: F401,F403
from ._tumble import IntegrationError, parameterization_names  # noqa: F401

__version__ = "0.1.0"
