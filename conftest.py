"""Shared by every test, doctest and docs example: the solver's disk cache is off, so no run
reads or writes the user's cache (tests of the cache turn it on in a folder of their own)."""

import os

os.environ["MECHGRADE_NO_CACHE"] = "1"
