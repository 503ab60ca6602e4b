"""mechgrade: automated checker and grader for engineering dynamics homework.

The pipeline, with imports pointing one way only::

    spec (load_problem) -> mechanics (model) -> solve -> grade -> report / export -> cli
"""

__version__ = "0.1.0"
