"""The expression language shared by problem specs and student answers (never ``eval``)."""
