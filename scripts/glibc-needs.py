"""The highest GLIBC symbol version each ELF file needs (its .gnu.version_r entries, as `objdump -T`
shows them per symbol), checked against a floor: the file starts on any glibc from that version on.

    python scripts/glibc-needs.py 2.17 target/dist/wearsim wearsim/_wearsim.abi3.so

Needs pyelftools (a dependency of auditwheel, in target/build-venv).
"""

import sys

from elftools.elf.elffile import ELFFile
from elftools.elf.gnuversions import GNUVerNeedSection


def glibc_versions(path):
    with open(path, "rb") as f:
        for section in ELFFile(f).iter_sections():
            if isinstance(section, GNUVerNeedSection):
                for _, needed in section.iter_versions():
                    for version in needed:
                        if version.name.startswith("GLIBC_") and version.name[6:7].isdigit():
                            yield tuple(int(x) for x in version.name[6:].split("."))


def main():
    floor = tuple(int(x) for x in sys.argv[1].split("."))
    failed = False
    for path in sys.argv[2:]:
        versions = sorted(set(glibc_versions(path)))
        if not versions:
            sys.exit(f"{path}: no GLIBC symbol versions found (not a dynamically linked glibc program?)")
        highest = ".".join(map(str, versions[-1]))
        verdict = "ok" if versions[-1] <= floor else f"NEWER than {sys.argv[1]}"
        print(f"{path}: needs GLIBC_{highest} at most ({len(versions)} versions) — {verdict}")
        failed |= versions[-1] > floor
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
