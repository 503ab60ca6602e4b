"""Hatch build hook: the specs shipped in the wheel name the schema where the wheel puts it.

In the repository a spec in ``problems/`` names the schema as
``../src/mechgrade/spec/problem.schema.json``; in the wheel the specs sit in
``mechgrade/problems`` (and ``mechgrade/examples/...``) beside ``mechgrade/spec``, so each
shipped copy gets its first line rewritten to the path that holds there.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

try:
    from hatchling.builders.hooks.plugin.interface import BuildHookInterface
except ImportError:  # the tests read wheel_modeline without hatchling installed
    BuildHookInterface = object  # type: ignore[assignment,misc]

MODELINE = "# yaml-language-server: $schema="
SHIPPED = ("problems", "examples")


def wheel_modeline(text: str, depth: int) -> str:
    """``text`` with its modeline (if any) pointing ``depth`` folders up, then at
    ``spec/problem.schema.json``."""
    if not text.startswith(MODELINE):
        return text
    rest = text[text.index("\n"):] if "\n" in text else ""
    return MODELINE + "../" * depth + "spec/problem.schema.json" + rest


class ModelineHook(BuildHookInterface):
    PLUGIN_NAME = "custom"

    def initialize(self, version: str, build_data: dict) -> None:
        if self.target_name != "wheel" or version == "editable":  # editable: the repository's
            return
        root = Path(self.root)
        out = Path(tempfile.mkdtemp(prefix="mechgrade-specs-"))
        for folder in SHIPPED:
            for path in sorted((root / folder).rglob("*.yaml")):
                relative = path.relative_to(root)
                text = path.read_text(encoding="utf-8")
                fixed = wheel_modeline(text, len(relative.parts) - 1)
                if fixed == text:
                    continue
                target = out / relative
                target.parent.mkdir(parents=True, exist_ok=True)
                target.write_text(fixed, encoding="utf-8", newline="\n")
                build_data["force_include"][str(target)] = f"mechgrade/{relative.as_posix()}"
