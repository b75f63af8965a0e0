"""Prints the oldest versions pyproject.toml allows, one `name==version` a line, for the test leg that
installs them (scripts/test-floors.sh): the runtime dependencies and those of the extras the Python
tests exercise (dask, examples, fields, test). Packages named in SKIPPED are left out; the tests that
need them skip with a reason naming the missing package."""

import re
import sys
import tomllib
from pathlib import Path

EXTRAS = ("dask", "examples", "fields", "test")
# tamaas and SurfaceTopography are cross-checks and an optional reader: their tests skip without them.
SKIPPED = {"tamaas", "surfacetopography"}

project = tomllib.loads((Path(__file__).resolve().parent.parent / "pyproject.toml").read_text())["project"]
requirements = list(project["dependencies"])
for extra in EXTRAS:
    requirements += project["optional-dependencies"][extra]

floors: dict[str, str] = {}
for requirement in requirements:
    match = re.fullmatch(r"([A-Za-z0-9_.-]+)(\[[^\]]*\])?\s*(>=\s*([^,;\s]+))?.*", requirement)
    if match is None:
        sys.exit(f"scripts/floors.py: cannot read the requirement {requirement!r} of pyproject.toml")
    name, extras, _, floor = match.groups()
    if name.lower() in SKIPPED:
        continue
    if floor is None:
        sys.exit(f"scripts/floors.py: {requirement!r} has no floor (>=); give it one in pyproject.toml")
    pin = f"{name}{extras or ''}=={floor}"
    if floors.get(name, pin) != pin:
        sys.exit(f"scripts/floors.py: two floors for {name}: {floors[name]} and {pin}")
    floors[name] = pin
print("\n".join(floors.values()))
