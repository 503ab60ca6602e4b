"""Shared by every test, doctest and docs example: the solver's disk cache is off, so no run
reads or writes the user's cache (tests of the cache turn it on in a folder of their own).

Hypothesis runs without its per-example deadline: tests never assert timings, and on a loaded
CI machine a first example that imports sympy can take longer than any fixed deadline
or health check of generation speed."""

import os

from hypothesis import HealthCheck, settings

os.environ["MECHGRADE_NO_CACHE"] = "1"

settings.register_profile("mechgrade", deadline=None,
                           suppress_health_check=[HealthCheck.too_slow])
settings.load_profile("mechgrade")
